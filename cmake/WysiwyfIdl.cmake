# wysiwyf_idl_library(NAME <target> IDL <files...> [INCLUDE_DIRS <dirs>] [LINK <targets>])
# Runs fastddsgen on each IDL at build time into ${CMAKE_BINARY_DIR}/generated/wysiwyf/idl and
# compiles the generated type and TypeSupport code into a shared library. Generated code stays in
# the build tree.
set(WYSIWYF_IDL_OUT ${CMAKE_BINARY_DIR}/generated/wysiwyf/idl)
file(MAKE_DIRECTORY ${WYSIWYF_IDL_OUT})

function(wysiwyf_idl_library)
  cmake_parse_arguments(ARG "" "NAME" "IDL;INCLUDE_DIRS;LINK" ${ARGN})
  set(sources)
  set(include_flags)
  foreach(dir ${ARG_INCLUDE_DIRS})
    list(APPEND include_flags -I ${dir})
  endforeach()
  foreach(idl ${ARG_IDL})
    get_filename_component(base ${idl} NAME_WE)
    get_filename_component(abs ${idl} ABSOLUTE)
    set(outs ${WYSIWYF_IDL_OUT}/${base}.h ${WYSIWYF_IDL_OUT}/${base}.cxx
             ${WYSIWYF_IDL_OUT}/${base}PubSubTypes.h ${WYSIWYF_IDL_OUT}/${base}PubSubTypes.cxx)
    # fastddsgen also writes the code of every IDL the file includes: generating into the shared
    # folder would rewrite (say) std_msgs.h after its library was built and relink everything
    # on the next build. Each file is generated in a folder of its own; only its four files are
    # copied out.
    set(private ${CMAKE_CURRENT_BINARY_DIR}/fastddsgen/${base})
    add_custom_command(
      OUTPUT ${outs}
      COMMAND ${CMAKE_COMMAND} -E make_directory ${private}
      COMMAND ${FASTDDSGEN} -replace -cs -d ${private} ${include_flags} ${abs}
              > ${CMAKE_CURRENT_BINARY_DIR}/${base}.fastddsgen.log
      COMMAND ${CMAKE_COMMAND} -E copy ${private}/${base}.h ${private}/${base}.cxx ${private}/${base}PubSubTypes.h
              ${private}/${base}PubSubTypes.cxx ${WYSIWYF_IDL_OUT}
      DEPENDS ${abs}
      COMMENT "fastddsgen ${base}.idl"
      VERBATIM)
    list(APPEND sources ${WYSIWYF_IDL_OUT}/${base}.cxx ${WYSIWYF_IDL_OUT}/${base}PubSubTypes.cxx)
  endforeach()
  add_library(${ARG_NAME} SHARED ${sources})
  target_include_directories(${ARG_NAME} PUBLIC ${CMAKE_BINARY_DIR}/generated)
  target_include_directories(${ARG_NAME} PRIVATE ${WYSIWYF_IDL_OUT})
  target_link_libraries(${ARG_NAME} PUBLIC fastrtps fastcdr ${ARG_LINK})
  # Generated code is not ours to warn about.
  target_compile_options(${ARG_NAME} PRIVATE -w)
endfunction()
