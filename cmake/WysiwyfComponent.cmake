# wysiwyf_add_component(<type> SOURCES <files...> [LINK <targets...>] [OUTPUT_DIR <dir>])
# Builds component type <type> as wysiwyf_<type>.so (a MODULE library: loaded with dlopen, never
# linked) into ${CMAKE_BINARY_DIR}/lib/wysiwyf, where the loader looks for it from programs built
# in the same tree (a test in ${CMAKE_BINARY_DIR} or ${CMAKE_BINARY_DIR}/bin finds it with no
# environment variable), and installs it into <libdir>/wysiwyf. OUTPUT_DIR puts it elsewhere and
# does not install it (test-only components). Used by this project and, installed, by its users
# (find_package(wysiwyf)).
function(wysiwyf_add_component type)
  cmake_parse_arguments(ARG "" "OUTPUT_DIR" "SOURCES;LINK" ${ARGN})
  if(NOT ARG_SOURCES)
    message(FATAL_ERROR "wysiwyf_add_component(${type}): expected SOURCES <files...>")
  endif()
  set(target component_${type})
  add_library(${target} MODULE ${ARG_SOURCES})
  set_property(GLOBAL APPEND PROPERTY WYSIWYF_COMPONENT_TARGETS ${target})  # (what runs whole pipelines depends on all)
  if(NOT ARG_OUTPUT_DIR)
    set(ARG_OUTPUT_DIR ${CMAKE_BINARY_DIR}/lib/wysiwyf)
    install(TARGETS ${target} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/wysiwyf)
  endif()
  set_target_properties(${target} PROPERTIES
    PREFIX ""
    OUTPUT_NAME wysiwyf_${type}
    LIBRARY_OUTPUT_DIRECTORY ${ARG_OUTPUT_DIR}
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON
    # Installed: the core one folder up (or in the wysiwyf prefix), message libraries in messages/.
    INSTALL_RPATH "$ORIGIN/..;$ORIGIN/messages${WYSIWYF_LIBRARY_DIR_RPATH}")
  target_link_libraries(${target} PRIVATE wysiwyf::core ${ARG_LINK})
  target_link_options(${target} PRIVATE -Wl,--no-undefined)
endfunction()
