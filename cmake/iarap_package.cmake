# `cpack -G DEB` in the build folder: a Debian package of everything `cmake --install` puts (tool, library,
# headers, CMake package, web app, Python module, docs). It installs under CMAKE_INSTALL_PREFIX as
# configured, so the paths computed for it (RPATHs, the Python folder) hold: configure with
# -DCMAKE_INSTALL_PREFIX=/usr for a package in Debian's own layout, the default /usr/local for a local one.
# Run-time dependencies come from dpkg-shlibdeps (libcholmod3, libgomp1, ...); the Python module also
# needs numpy and scipy at import.
set(CPACK_PACKAGE_NAME iarap)
set(CPACK_PACKAGE_VENDOR "iarap developers")
set(CPACK_PACKAGE_CONTACT "iarap developers <iarap@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_RESOURCE_FILE_LICENSE ${PROJECT_SOURCE_DIR}/LICENSE)
set(CPACK_PACKAGING_INSTALL_PREFIX ${CMAKE_INSTALL_PREFIX})
set(CPACK_GENERATOR DEB)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# libiarap.so.0 ships in this package; dpkg-shlibdeps finds it there instead of asking for another one.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS ${PROJECT_BINARY_DIR}/src)
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "python3-numpy, python3-scipy")
# deform --volume runs the tetgen program (AGPL: not linked, so not a dependency)
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "tetgen")
# Linked with Debian's CHOLMOD (supernodal module: GPL), the binaries are distributed under the GPL; the
# package says so beside this project's own MIT license (README, "Licenses").
# CPack puts CPACK_PACKAGE_DESCRIPTION_SUMMARY on the Description line and this text below it.
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION "A C++17 library, the `iarap` command-line tool with a web viewer and a Python
module for as-rigid-as-possible surface deformation (original ARAP, spokes-and-rims, iARAP).
iarap's own code is MIT-licensed; these binaries link Debian's CHOLMOD, whose supernodal module is
GPL-licensed, so the package as a whole is distributed under the terms of the GPL.")
include(CPack)
