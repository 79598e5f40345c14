# What `cmake --install` adds beyond the targets' own rules: the CMake package (find_package(wysiwyf)
# with the imported targets and the users' functions), the config files, and a .deb of it all (cpack).
include(CMakePackageConfigHelpers)

install(EXPORT wysiwyfTargets NAMESPACE wysiwyf:: DESTINATION ${WYSIWYF_INSTALL_CMAKE_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/wysiwyfConfig.cmake.in
  ${CMAKE_BINARY_DIR}/cmake/wysiwyfConfig.cmake
  INSTALL_DESTINATION ${WYSIWYF_INSTALL_CMAKE_DIR}
  PATH_VARS CMAKE_INSTALL_LIBDIR CMAKE_INSTALL_BINDIR WYSIWYF_INSTALL_CONFIG_DIR WYSIWYF_INSTALL_IDL_DIR)
# The kernel's build id pins components to the exact headers: only this version is compatible.
write_basic_package_version_file(${CMAKE_BINARY_DIR}/cmake/wysiwyfConfigVersion.cmake
  COMPATIBILITY ExactVersion)
install(FILES ${CMAKE_BINARY_DIR}/cmake/wysiwyfConfig.cmake ${CMAKE_BINARY_DIR}/cmake/wysiwyfConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/WysiwyfComponent.cmake ${PROJECT_SOURCE_DIR}/cmake/WysiwyfMessages.cmake
        DESTINATION ${WYSIWYF_INSTALL_CMAKE_DIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/config/ DESTINATION ${WYSIWYF_INSTALL_CONFIG_DIR})
# The manual: README, the guides and references (`wysiwyf --help` points at command-line.md), the licence.
install(FILES ${PROJECT_SOURCE_DIR}/README.md ${PROJECT_SOURCE_DIR}/LICENSE DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR} FILES_MATCHING PATTERN "*.md")

# cpack -G DEB (scripts/package): a lab installs it with apt install ./wysiwyf_*.deb.
set(CPACK_PACKAGE_NAME wysiwyf)
set(CPACK_PACKAGE_VENDOR "WYSIWYF")
set(CPACK_PACKAGE_CONTACT "WYSIWYF developers <wysiwyf@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "WYSIWYF visual/haptic encountered-type display: kernel, components, tools, SDK")
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_STRIP_FILES ON)  # the build is RelWithDebInfo: 477 MB installed with debug info
# What the programs and components load (found by dpkg-shlibdeps), and what a user's component
# build needs (the SDK: headers of the libraries our headers include, fastddsgen, a compiler).
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS ${CMAKE_BINARY_DIR}/lib)
set(CPACK_DEBIAN_PACKAGE_DEPENDS
    "libfastrtps-dev, libfastcdr-dev, fastddsgen, libeigen3-dev, libyaml-cpp-dev, cmake, g++, libgtest-dev, liburdfdom-dev, liborocos-kdl-dev")
include(CPack)
