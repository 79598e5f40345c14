# wysiwyf_idl_library(NAME <target> EXPORT_NAME <name> IDL <files...> [INCLUDE_DIRS <dirs>] [LINK <targets>])
# The project's own message types: runs fastddsgen (with -typeobject, so tools can read the types
# at run time) on each IDL at build time into ${CMAKE_BINARY_DIR}/generated/wysiwyf/idl, compiles
# the generated code into a shared library, and installs the library, its headers and the IDL
# (users' IDL files include ours). Users' types go through wysiwyf_add_messages(); both generate
# with wysiwyf_fastddsgen() (WysiwyfMessages.cmake).
set(WYSIWYF_IDL_OUT ${CMAKE_BINARY_DIR}/generated/wysiwyf/idl)
file(MAKE_DIRECTORY ${WYSIWYF_IDL_OUT})

function(wysiwyf_idl_library)
  cmake_parse_arguments(ARG "" "NAME;EXPORT_NAME" "IDL;INCLUDE_DIRS;LINK" ${ARGN})
  set(sources)
  set(headers)
  foreach(idl ${ARG_IDL})
    wysiwyf_fastddsgen(${idl} OUT_DIR ${WYSIWYF_IDL_OUT} WORK_DIR ${CMAKE_CURRENT_BINARY_DIR}/fastddsgen
                       INCLUDE_DIRS ${ARG_INCLUDE_DIRS} SOURCES sources HEADERS headers)
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
  install(FILES ${headers} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/wysiwyf/idl COMPONENT dev)
  install(FILES ${ARG_IDL} DESTINATION ${CMAKE_INSTALL_DATADIR}/wysiwyf/idl)
endfunction()
