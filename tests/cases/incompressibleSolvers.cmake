# Incompressible pressure solvers (pcisph, pbf, relaxedPbf) through the real binary: the
# tutorials' one-word solver swap, plugin loading, and maxIterations reporting.
add_test(NAME IncompressibleSolvers.TutorialSwapDryRunAndMaxIterations
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/incompressibleSolvers.sh $<TARGET_FILE:spindriftSolver>
          ${PROJECT_SOURCE_DIR}/tutorials)
set_tests_properties(IncompressibleSolvers.TutorialSwapDryRunAndMaxIterations
  PROPERTIES ENVIRONMENT "SPINDRIFT_PLUGIN_PATH=${SPINDRIFT_PLUGIN_BUILD_DIR};OMP_NUM_THREADS=1" TIMEOUT 300)
