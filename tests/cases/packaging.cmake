# Packaging: the bash completion.
add_test(NAME Package.BashCompletion
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/bashCompletion.sh $<TARGET_FILE:spindriftSolver>
          ${PROJECT_SOURCE_DIR}/etc/bash-completion/spindrift)
set_tests_properties(Package.BashCompletion PROPERTIES LABELS package TIMEOUT 600)
