# Installs the library, headers, the tool and a CMake package so that find_package(iarap) works.
# The tool and the Python module find libiarap (and the web app) relative to themselves, so an installed
# tree works at any --prefix and keeps working when moved (no LD_LIBRARY_PATH, no ldconfig).
include(CMakePackageConfigHelpers)
install(TARGETS iarap EXPORT iarapTargets
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY include/iarap DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT iarapTargets NAMESPACE iarap:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/iarap)
configure_package_config_file(cmake/iarapConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/iarapConfig.cmake INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/iarap)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/iarapConfigVersion.cmake
  COMPATIBILITY SameMajorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/iarapConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/iarapConfigVersion.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/iarap)
install(FILES LICENSE README.md CHANGELOG.md CITATION.cff DESTINATION ${CMAKE_INSTALL_DOCDIR})
