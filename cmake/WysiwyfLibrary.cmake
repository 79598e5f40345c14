# wysiwyf_add_library(<name> [HEADER_ONLY] [INSTALL] SOURCES <files...> [PUBLIC <targets...>]
#                     [PRIVATE <targets...>])
# A library shared between components (and apps, tests, benchmarks): libs/<area>/<name>/, built
# as the static, position-independent target wysiwyf_<name> (component .so files link it in). Its
# users link it and include its headers as "<name>/<header>.hpp" (its area's folder is on their
# include path). HEADER_ONLY makes an INTERFACE target.
# INSTALL puts it in the SDK: `cmake --install` exports it as wysiwyf::<name> (find_package(wysiwyf))
# with its headers under include/wysiwyf/libs/<name>/, so a user's component out of tree links it
# and includes "<name>/<header>.hpp" as here. Every library it links PUBLIC must be INSTALL too.
function(wysiwyf_add_library name)
  cmake_parse_arguments(ARG "HEADER_ONLY;INSTALL" "" "SOURCES;PUBLIC;PRIVATE" ${ARGN})
  set(target wysiwyf_${name})
  get_filename_component(area_dir ${CMAKE_CURRENT_SOURCE_DIR} DIRECTORY)
  set(includes $<BUILD_INTERFACE:${area_dir}> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/wysiwyf/libs>)
  if(ARG_HEADER_ONLY)
    add_library(${target} INTERFACE)
    target_include_directories(${target} INTERFACE ${includes})
    target_link_libraries(${target} INTERFACE ${ARG_PUBLIC})
  else()
    add_library(${target} STATIC ${ARG_SOURCES})
    set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE ON)
    target_include_directories(${target} PUBLIC ${includes})
    target_link_libraries(${target} PUBLIC ${ARG_PUBLIC} PRIVATE ${ARG_PRIVATE})
  endif()
  if(ARG_INSTALL)
    set_target_properties(${target} PROPERTIES EXPORT_NAME ${name})
    install(TARGETS ${target} EXPORT wysiwyfTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev)
    install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/wysiwyf/libs/${name}
            COMPONENT dev FILES_MATCHING PATTERN "*.hpp")
  endif()
endfunction()
