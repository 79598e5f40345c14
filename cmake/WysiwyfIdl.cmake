# wysiwyf_idl_library(NAME <target> EXPORT_NAME <name> IDL <files...> [INCLUDE_DIRS <dirs>] [LINK <targets>])
# The project's own message types: runs fastddsgen (with -typeobject, so tools can read the types
# at run time) on each IDL at build time into ${CMAKE_BINARY_DIR}/generated/wysiwyf/idl, compiles
# the generated code into a shared library, and installs the library, its headers and the IDL
# (users' IDL files include ours). Users' types go through wysiwyf_add_messages().
set(WYSIWYF_IDL_OUT ${CMAKE_BINARY_DIR}/generated/wysiwyf/idl)
file(MAKE_DIRECTORY ${WYSIWYF_IDL_OUT})

function(wysiwyf_idl_library)
  cmake_parse_arguments(ARG "" "NAME;EXPORT_NAME" "IDL;INCLUDE_DIRS;LINK" ${ARGN})
  set(sources)
  set(headers)
  set(include_flags)
  foreach(dir ${ARG_INCLUDE_DIRS})
    list(APPEND include_flags -I ${dir})
  endforeach()
  foreach(idl ${ARG_IDL})
    get_filename_component(base ${idl} NAME_WE)
    get_filename_component(abs ${idl} ABSOLUTE)
    set(generated ${base}.h ${base}.cxx ${base}PubSubTypes.h ${base}PubSubTypes.cxx ${base}TypeObject.h
                  ${base}TypeObject.cxx)
    list(TRANSFORM generated PREPEND ${WYSIWYF_IDL_OUT}/ OUTPUT_VARIABLE outs)
    # fastddsgen also writes the code of every IDL the file includes: generating into the shared
    # folder would rewrite (say) std_msgs.h after its library was built and relink everything
    # on the next build. Each file is generated in a folder of its own; only its files are
    # copied out.
    set(private ${CMAKE_CURRENT_BINARY_DIR}/fastddsgen/${base})
    set(private_outs ${private}/${base}.h ${private}/${base}.cxx ${private}/${base}PubSubTypes.h
                     ${private}/${base}PubSubTypes.cxx ${private}/typeobject/${base}TypeObject.h
                     ${private}/typeobject/${base}TypeObject.cxx)
    add_custom_command(
      OUTPUT ${outs}
      COMMAND ${CMAKE_COMMAND} -E make_directory ${private}/typeobject
      # Two passes: the structs without -typeobject (with it, every constructor registers every
      # type in Fast DDS's factory: a lock and map lookups per message on the tick path), and
      # the type objects alone, registered once by the tools that read types at run time.
      COMMAND ${FASTDDSGEN} -replace -cs -d ${private} ${include_flags} ${abs} > ${CMAKE_CURRENT_BINARY_DIR}/${base}.fastddsgen.log
      COMMAND ${FASTDDSGEN} -replace -cs -typeobject -d ${private}/typeobject ${include_flags} ${abs} >> ${CMAKE_CURRENT_BINARY_DIR}/${base}.fastddsgen.log
      COMMAND ${CMAKE_COMMAND} -E copy ${private_outs} ${WYSIWYF_IDL_OUT}
      DEPENDS ${abs}
      COMMENT "fastddsgen ${base}.idl"
      VERBATIM)
    list(APPEND sources ${WYSIWYF_IDL_OUT}/${base}.cxx ${WYSIWYF_IDL_OUT}/${base}PubSubTypes.cxx
                        ${WYSIWYF_IDL_OUT}/${base}TypeObject.cxx)
    list(APPEND headers ${WYSIWYF_IDL_OUT}/${base}.h ${WYSIWYF_IDL_OUT}/${base}PubSubTypes.h
                        ${WYSIWYF_IDL_OUT}/${base}TypeObject.h)
  endforeach()
  add_library(${ARG_NAME} SHARED ${sources})
  add_library(wysiwyf::${ARG_EXPORT_NAME} ALIAS ${ARG_NAME})
  set_target_properties(${ARG_NAME} PROPERTIES EXPORT_NAME ${ARG_EXPORT_NAME})
  # "wysiwyf/idl/x.h" from anywhere; the generated headers include each other as "x.h".
  target_include_directories(${ARG_NAME} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_BINARY_DIR}/generated> $<BUILD_INTERFACE:${WYSIWYF_IDL_OUT}>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/wysiwyf/idl>)
  target_link_libraries(${ARG_NAME} PUBLIC fastrtps fastcdr ${ARG_LINK})
  # Generated code is not ours to warn about.
  target_compile_options(${ARG_NAME} PRIVATE -w)
  install(TARGETS ${ARG_NAME} EXPORT wysiwyfTargets LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(FILES ${headers} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/wysiwyf/idl)
  install(FILES ${ARG_IDL} DESTINATION ${CMAKE_INSTALL_DATADIR}/wysiwyf/idl)
endfunction()
