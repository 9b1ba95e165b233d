# Incompressible pressure solvers (pcisph, pbf, relaxedPbf) through the real binary: the
# tutorials' one-word solver swap, plugin loading, and maxIterations reporting.
add_test(NAME IncompressibleSolvers.TutorialSwapDryRunAndMaxIterations
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/incompressibleSolvers.sh $<TARGET_FILE:spindriftSolver>
          ${PROJECT_SOURCE_DIR}/tutorials)
set_tests_properties(IncompressibleSolvers.TutorialSwapDryRunAndMaxIterations
  PROPERTIES ENVIRONMENT "SPINDRIFT_PLUGIN_PATH=${SPINDRIFT_PLUGIN_BUILD_DIR};OMP_NUM_THREADS=1" TIMEOUT 300)

# Every pressure solver at walls (issues 34.4, 35): the first row half a spacing over the floor,
# nothing past a wall's face, no clumping in still water or a short dam break (solverWalls.sh)
if(PVPYTHON)
  add_test(NAME IncompressibleSolvers.WallsHoldForEverySolver
    COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/solverWalls.sh $<TARGET_FILE:spindriftSolver> ${PVPYTHON})
  set_tests_properties(IncompressibleSolvers.WallsHoldForEverySolver PROPERTIES
    ENVIRONMENT "SPINDRIFT_PLUGIN_PATH=${SPINDRIFT_PLUGIN_BUILD_DIR};OMP_NUM_THREADS=1" TIMEOUT 900 LABELS validation)
endif()
