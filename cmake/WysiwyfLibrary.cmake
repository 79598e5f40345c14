# wysiwyf_add_library(<name> [HEADER_ONLY] SOURCES <files...> [PUBLIC <targets...>] [PRIVATE <targets...>])
# A library shared between components (and apps, tests, benchmarks): libs/<name>/, built as the
# static, position-independent target wysiwyf_<name> (component .so files link it in). Its users
# include its headers as "<name>/<header>.hpp". HEADER_ONLY makes an INTERFACE target.
function(wysiwyf_add_library name)
  cmake_parse_arguments(ARG "HEADER_ONLY" "" "SOURCES;PUBLIC;PRIVATE" ${ARGN})
  set(target wysiwyf_${name})
  if(ARG_HEADER_ONLY)
    add_library(${target} INTERFACE)
    target_include_directories(${target} INTERFACE ${PROJECT_SOURCE_DIR}/libs)
    target_link_libraries(${target} INTERFACE ${ARG_PUBLIC})
    return()
  endif()
  add_library(${target} STATIC ${ARG_SOURCES})
  set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  target_include_directories(${target} PUBLIC ${PROJECT_SOURCE_DIR}/libs)
  target_link_libraries(${target} PUBLIC ${ARG_PUBLIC} PRIVATE ${ARG_PRIVATE})
endfunction()
