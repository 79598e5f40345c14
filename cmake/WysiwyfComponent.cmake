# wysiwyf_add_component(<type> SOURCES <files...> [LINK <targets...>])
# Builds component type <type> as wysiwyf_<type>.so (a MODULE library: loaded with dlopen, never
# linked) into the directory the loader searches. OUTPUT_DIR overrides that (test components).
function(wysiwyf_add_component type)
  cmake_parse_arguments(ARG "" "OUTPUT_DIR" "SOURCES;LINK" ${ARGN})
  set(target component_${type})
  add_library(${target} MODULE ${ARG_SOURCES})
  if(NOT ARG_OUTPUT_DIR)
    set(ARG_OUTPUT_DIR ${WYSIWYF_COMPONENT_BUILD_DIR})
    install(TARGETS ${target} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/wysiwyf)
  endif()
  set_target_properties(${target} PROPERTIES
    PREFIX ""
    OUTPUT_NAME wysiwyf_${type}
    LIBRARY_OUTPUT_DIRECTORY ${ARG_OUTPUT_DIR}
    CXX_VISIBILITY_PRESET hidden
    VISIBILITY_INLINES_HIDDEN ON)
  target_link_libraries(${target} PRIVATE wysiwyf_core ${ARG_LINK})
  target_link_options(${target} PRIVATE -Wl,--no-undefined)
endfunction()
