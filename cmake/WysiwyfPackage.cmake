# What `cmake --install` adds beyond the targets' own rules: the CMake package (find_package(wysiwyf)
# with the imported targets and the users' functions), the config files, and a .deb of it all (cpack).
include(CMakePackageConfigHelpers)

install(EXPORT wysiwyfTargets NAMESPACE wysiwyf:: DESTINATION ${WYSIWYF_INSTALL_CMAKE_DIR} COMPONENT dev)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/wysiwyfConfig.cmake.in
  ${CMAKE_BINARY_DIR}/cmake/wysiwyfConfig.cmake
  INSTALL_DESTINATION ${WYSIWYF_INSTALL_CMAKE_DIR}
  PATH_VARS CMAKE_INSTALL_LIBDIR CMAKE_INSTALL_BINDIR WYSIWYF_INSTALL_CONFIG_DIR WYSIWYF_INSTALL_IDL_DIR)
# The kernel's build id pins components to the exact headers: only this version is compatible.
write_basic_package_version_file(${CMAKE_BINARY_DIR}/cmake/wysiwyfConfigVersion.cmake
  COMPATIBILITY ExactVersion)
install(FILES ${CMAKE_BINARY_DIR}/cmake/wysiwyfConfig.cmake ${CMAKE_BINARY_DIR}/cmake/wysiwyfConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/WysiwyfComponent.cmake ${PROJECT_SOURCE_DIR}/cmake/WysiwyfMessages.cmake
        DESTINATION ${WYSIWYF_INSTALL_CMAKE_DIR} COMPONENT dev)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/config/ DESTINATION ${WYSIWYF_INSTALL_CONFIG_DIR})
# The manual: README, the guides and references (`wysiwyf --help` points at command-line.md), the
# licence (as Debian's copyright file, in each package's doc folder).
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE DESTINATION ${CMAKE_INSTALL_DOCDIR} RENAME copyright)
install(FILES ${PROJECT_SOURCE_DIR}/LICENSE DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/wysiwyf-dev RENAME copyright
        COMPONENT dev)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR} FILES_MATCHING PATTERN "*.md")

# cpack -G DEB (scripts/package): two packages, as Debian splits a library. `wysiwyf` is what a
# lab runs (apt install ./wysiwyf_*.deb): programs, components, configuration, manual; its
# dependencies are the shared libraries they load (dpkg-shlibdeps). `wysiwyf-dev` is what
# building a component out of tree needs: headers, the CMake package, and the toolchain.
set(CPACK_PACKAGE_NAME wysiwyf)
set(CPACK_PACKAGE_VENDOR "WYSIWYF")
set(CPACK_PACKAGE_CONTACT "WYSIWYF developers <wysiwyf@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "WYSIWYF visual/haptic encountered-type display")
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL runtime dev)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_STRIP_FILES ON)  # the build is RelWithDebInfo: 477 MB installed with debug info
set(CPACK_DEBIAN_RUNTIME_PACKAGE_NAME wysiwyf)
set(CPACK_COMPONENT_RUNTIME_DESCRIPTION
    "WYSIWYF visual/haptic encountered-type display: kernel, components, tools, configuration")
set(CPACK_DEBIAN_RUNTIME_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS ${CMAKE_BINARY_DIR}/lib)
set(CPACK_DEBIAN_DEV_PACKAGE_NAME wysiwyf-dev)
set(CPACK_DEBIAN_DEV_PACKAGE_SECTION libdevel)
set(CPACK_COMPONENT_DEV_DESCRIPTION "WYSIWYF SDK: headers and CMake package for components and message types")
set(CPACK_COMPONENT_DEV_DEPENDS runtime)  # (with the next line: Depends: wysiwyf (= this version))
set(CPACK_DEBIAN_ENABLE_COMPONENT_DEPENDS ON)
# The headers of the libraries ours include, the IDL compiler and a compiler.
set(CPACK_DEBIAN_DEV_PACKAGE_DEPENDS
    "libfastrtps-dev, libfastcdr-dev, fastddsgen, libeigen3-dev, libyaml-cpp-dev, cmake, g++, libgtest-dev, liburdfdom-dev, liborocos-kdl-dev")
include(CPack)
