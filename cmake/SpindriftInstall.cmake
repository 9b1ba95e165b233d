# Spindrift — the development package: what `cmake --install` adds to the targets' own rules
# (libsrc/: library and headers, plugins/, applications/), and the Debian package
# (`cpack -G DEB` in the build directory).
#
#   <prefix>/bin/spindrift ...                     solver and utilities
#   <prefix>/include/spindrift/*.hpp               the core's headers (plugins build against them)
#   <prefix>/lib/libspindrift.so.<version>         the core, SONAME libspindrift.so.<SOVERSION>
#   <prefix>/lib/spindrift/plugins/                the models (found by the installed solver)
#   <prefix>/lib/cmake/Spindrift/                  find_package(Spindrift): Spindrift::spindrift,
#                                                  spindrift_add_plugin()
#   <prefix>/share/spindrift/etc/                  bashrc, RunFunctions, plugin templates
#   <prefix>/share/spindrift/tutorials/            the tutorials' input (no results)
#   <prefix>/share/bash-completion/completions/spindrift
include(CMakePackageConfigHelpers)

set(SPINDRIFT_CMAKE_INSTALL_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/Spindrift)
install(EXPORT SpindriftTargets NAMESPACE Spindrift:: DESTINATION ${SPINDRIFT_CMAKE_INSTALL_DIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/SpindriftConfig.cmake.in
  ${PROJECT_BINARY_DIR}/SpindriftConfig.cmake
  INSTALL_DESTINATION ${SPINDRIFT_CMAKE_INSTALL_DIR}
  PATH_VARS CMAKE_INSTALL_LIBDIR)
# before 1.0, a minor version may change the plugin interface: 0.3.x plugins need a 0.3.y core
write_basic_package_version_file(${PROJECT_BINARY_DIR}/SpindriftConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/SpindriftConfig.cmake ${PROJECT_BINARY_DIR}/SpindriftConfigVersion.cmake
  ${PROJECT_SOURCE_DIR}/cmake/SpindriftPlugin.cmake
  DESTINATION ${SPINDRIFT_CMAKE_INSTALL_DIR})

# etc/ as in the tree (the tutorials' Allrun look for <prefix>/share/spindrift/etc/RunFunctions
# beside the spindrift on PATH), and the completion where bash-completion loads it by itself
install(DIRECTORY ${PROJECT_SOURCE_DIR}/etc/ DESTINATION ${CMAKE_INSTALL_DATADIR}/spindrift/etc
  USE_SOURCE_PERMISSIONS)
install(FILES ${PROJECT_SOURCE_DIR}/etc/bash-completion/spindrift
  DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions)

# The tutorials' input: what cloneCase (etc/RunFunctions) copies, never results a tutorial run
# in the source tree left behind (time directories, logs, .pvd, postProcessing/, plots).
install(DIRECTORY ${PROJECT_SOURCE_DIR}/tutorials DESTINATION ${CMAKE_INSTALL_DATADIR}/spindrift
  USE_SOURCE_PERMISSIONS
  REGEX "/[0-9][0-9.eE+-]*$" EXCLUDE
  REGEX "/\\.[0-9][^/]*\\.tmp$" EXCLUDE
  REGEX "\\.pvd(\\.tmp)?$" EXCLUDE
  REGEX "/log\\.[^/]*$" EXCLUDE
  REGEX "/run\\.log$" EXCLUDE
  REGEX "/(postProcessing|run|__pycache__)$" EXCLUDE
  REGEX "\\.png$" EXCLUDE)

# Debian package: cpack -G DEB -> spindrift_<version>_<arch>.deb, installing into /usr.
# Depends are read from the binaries by dpkg-shlibdeps (package dpkg-dev).
set(SPINDRIFT_PACKAGE_CONTACT "Spindrift maintainers <maintainers@users.noreply.h-seed-c9307578.example>"
  CACHE STRING "Maintainer field of the Debian package")
set(CPACK_PACKAGE_NAME spindrift)
set(CPACK_PACKAGE_VENDOR "Spindrift")
set(CPACK_PACKAGE_CONTACT "${SPINDRIFT_PACKAGE_CONTACT}")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "SPH fluid solver with run-time selected model plugins")
if(SPINDRIFT_PRECISION STREQUAL "float")
  set(precisionNote "single precision (Scalar = float)")
else()
  set(precisionNote "double precision (Scalar = double)")
endif()
set(CPACK_PACKAGE_DESCRIPTION "Spindrift is a smoothed particle hydrodynamics solver shaped like an \
OpenFOAM application: every model (kernel, pressure, viscosity, integrator, boundary, force, \
function object) is a plugin library chosen by name in the case's dictionaries. The package holds \
the solver, the plugins, the tutorials, and what building plugins needs: headers, \
find_package(Spindrift) and templates in /usr/share/spindrift/etc/templates. Built in ${precisionNote}.")
if(SPINDRIFT_NATIVE)
  string(APPEND CPACK_PACKAGE_DESCRIPTION " Built with -march=native: it runs only on processors with \
the instruction set of the machine that built it (configure with -DSPINDRIFT_NATIVE=OFF for a \
portable package).")
endif()
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
# (CPack adds postinst/postrm running ldconfig, for lib/libspindrift.so)
# Depends: what the binaries link, read by dpkg-shlibdeps. The solver reads and writes .vtp with
# ParaView's VTK (libvtk*-pv5.11, built against paraview-dev), and Debian 12 ships those libraries
# in the package `paraview` itself: it is the one package that holds them (libvtk9.1 is another
# VTK, and libvtk9-dev conflicts with python3-paraview, see README), so it stays a dependency.
# Recommends: python3-paraview (pvpython, pvbatch's python: the validation and tutorial scripts,
# etc/python/spindriftRender.py), python3-matplotlib (the plots of the validation cases and the
# bench and stress utilities), bash-completion (loads share/bash-completion/completions/spindrift),
# and what find_package(Spindrift) needs to build plugins. Suggests: xvfb (rendering without a
# display where pvbatch's offscreen rendering is not enough).
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS
  "python3-paraview, python3-matplotlib, bash-completion, cmake, g++, libeigen3-dev, libboost-dev")
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "xvfb")
# prerm: python caches (__pycache__) that a script run as root left under /usr/share/spindrift
# (etc/RunFunctions keeps the tutorials' scripts from writing them; python run by hand may),
# removed before the package's files, so that `apt remove` leaves no directory behind
file(CONFIGURE OUTPUT ${PROJECT_BINARY_DIR}/debian/prerm CONTENT [[#!/bin/sh
set -e
# python caches a script run as root left in the package's directories (not files of the package)
if [ -d "${DPKG_ROOT:-}/usr/share/spindrift" ]; then
    find "${DPKG_ROOT:-}/usr/share/spindrift" -depth -type d -name __pycache__ -exec rm -rf {} +
fi
exit 0
]] @ONLY)
file(CHMOD ${PROJECT_BINARY_DIR}/debian/prerm PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE
  GROUP_READ GROUP_EXECUTE WORLD_READ WORLD_EXECUTE)
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA ${PROJECT_BINARY_DIR}/debian/prerm)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION TRUE)
find_program(DPKG_SHLIBDEPS dpkg-shlibdeps)
if(DPKG_SHLIBDEPS)
  set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
  # the plugins and tools link libspindrift, which the package itself ships
  set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS ${CMAKE_BINARY_DIR}/lib)
else()
  message(STATUS "dpkg-shlibdeps not found (package dpkg-dev): the .deb's Depends are a fixed list")
  set(CPACK_DEBIAN_PACKAGE_DEPENDS "libc6, libstdc++6, libgcc-s1, libgomp1, libboost-program-options1.74.0, paraview")
endif()
include(CPack)
