# Spindrift — the development package: what `cmake --install` adds to the targets' own rules
# (libsrc/: library and headers, plugins/, applications/).
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
