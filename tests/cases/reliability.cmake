# Reliability: bad input through the real binary, interruptions, atomic writes, restarts.
add_test(NAME Reliability.BadInputsThroughTheSolver
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/badInputs.sh $<TARGET_FILE:spindriftSolver>
          ${PROJECT_SOURCE_DIR}/tutorials ${PROJECT_SOURCE_DIR}/tests/data/badInputs.table)
add_test(NAME Reliability.SignalsKillAndRuntimeModification
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/interruptions.sh $<TARGET_FILE:spindriftSolver>
          ${PROJECT_SOURCE_DIR}/tutorials $<TARGET_FILE:spindriftTestFaultyForce>)
set_tests_properties(Reliability.BadInputsThroughTheSolver Reliability.SignalsKillAndRuntimeModification
  PROPERTIES ENVIRONMENT "SPINDRIFT_PLUGIN_PATH=${SPINDRIFT_PLUGIN_BUILD_DIR}:${CMAKE_BINARY_DIR}/lib/testPlugins;OMP_NUM_THREADS=1"
  TIMEOUT 300)
add_test(NAME Reliability.OneSolverPerCase
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/caseLock.sh $<TARGET_FILE:spindriftSolver> ${PROJECT_SOURCE_DIR}/tutorials)
set_tests_properties(Reliability.OneSolverPerCase
  PROPERTIES ENVIRONMENT "SPINDRIFT_PLUGIN_PATH=${SPINDRIFT_PLUGIN_BUILD_DIR};OMP_NUM_THREADS=1" TIMEOUT 300)
# a full disk (a small tmpfs; skipped where one cannot be mounted)
add_test(NAME Reliability.FullDisk
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/fullDisk.sh $<TARGET_FILE:spindriftSolver> ${PROJECT_SOURCE_DIR}/tutorials)
set_tests_properties(Reliability.FullDisk
  PROPERTIES ENVIRONMENT "SPINDRIFT_PLUGIN_PATH=${SPINDRIFT_PLUGIN_BUILD_DIR};OMP_NUM_THREADS=1" TIMEOUT 300
  SKIP_RETURN_CODE 77)
# kills and restarts of a case with a moving wall and leapfrog, bit for bit (a short soak)
add_test(NAME Reliability.SoakQuick
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/soakQuick.sh $<TARGET_FILE:spindriftBench> ${PROJECT_SOURCE_DIR}/tutorials)
set_tests_properties(Reliability.SoakQuick
  PROPERTIES ENVIRONMENT "SPINDRIFT_PLUGIN_PATH=${SPINDRIFT_PLUGIN_BUILD_DIR};OMP_NUM_THREADS=1" TIMEOUT 300)
