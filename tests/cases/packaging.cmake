# Packaging: the installed development package used out of tree (templates, find_package), the
# Debian package's contents and control fields, and the bash completion.
add_test(NAME Package.InstalledSolverRunsAnOutOfTreeTemplatePlugin
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/devPackage.sh ${CMAKE_BINARY_DIR})
add_test(NAME Package.DebianPackageContentsAndDependencies
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/debPackage.sh ${CMAKE_BINARY_DIR} ${PROJECT_VERSION})
add_test(NAME Package.BashCompletion
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/bashCompletion.sh $<TARGET_FILE:spindriftSolver>
          ${PROJECT_SOURCE_DIR}/etc/bash-completion/spindrift)
set_tests_properties(Package.InstalledSolverRunsAnOutOfTreeTemplatePlugin Package.DebianPackageContentsAndDependencies
  Package.BashCompletion PROPERTIES ENVIRONMENT "OMP_NUM_THREADS=1" LABELS package TIMEOUT 600)
find_program(DPKG_DEB dpkg-deb)
if(NOT DPKG_DEB OR NOT DPKG_SHLIBDEPS)
  set_tests_properties(Package.DebianPackageContentsAndDependencies PROPERTIES DISABLED TRUE)
endif()
