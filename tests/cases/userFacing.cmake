# What a user sees (issue 34): -postProcess, the progress line, the docs against -listModels,
# Allclean without a solver, headless screenshots, the bench and stress utilities' options.
add_test(NAME Solver.PostProcessReproducesTheRun
  COMMAND ${CMAKE_CURRENT_LIST_DIR}/postProcess.sh $<TARGET_FILE:spindriftSolver> ${PROJECT_SOURCE_DIR}/tutorials)
add_test(NAME Solver.ProgressLineAtMostFourRedrawsASecond
  COMMAND ${CMAKE_CURRENT_LIST_DIR}/progressLine.sh $<TARGET_FILE:spindriftSolver> ${PROJECT_SOURCE_DIR}/tutorials)
add_test(NAME Docs.ModelsTableAndTutorialChoicesMatchListModels
  COMMAND ${CMAKE_CURRENT_LIST_DIR}/docsModels.py $<TARGET_FILE:spindriftSolver> ${PROJECT_SOURCE_DIR})
add_test(NAME Tutorials.AllcleanWithoutSolver
  COMMAND ${CMAKE_CURRENT_LIST_DIR}/allcleanWithoutSolver.sh ${PROJECT_SOURCE_DIR}/tutorials)
add_test(NAME Render.ScreenshotsWithoutDisplay
  COMMAND ${CMAKE_CURRENT_LIST_DIR}/render.sh $<TARGET_FILE:spindriftSolver> ${PROJECT_SOURCE_DIR}/tutorials)
add_test(NAME Render.DiffuseParticlesAndSurface3D
  COMMAND ${CMAKE_CURRENT_LIST_DIR}/render3D.sh $<TARGET_FILE:spindriftSolver> ${PROJECT_SOURCE_DIR}/tutorials)
add_test(NAME Bench.UtilityOptionsRefusedBeforeRunning
  COMMAND ${CMAKE_CURRENT_LIST_DIR}/utilityOptions.sh $<TARGET_FILE:spindriftBench> $<TARGET_FILE:spindriftStress>
          ${PROJECT_SOURCE_DIR}/tutorials/validation/hydrostaticTank2D)
set_tests_properties(Solver.PostProcessReproducesTheRun Solver.ProgressLineAtMostFourRedrawsASecond
  Docs.ModelsTableAndTutorialChoicesMatchListModels Tutorials.AllcleanWithoutSolver Render.ScreenshotsWithoutDisplay
  Render.DiffuseParticlesAndSurface3D Bench.UtilityOptionsRefusedBeforeRunning
  PROPERTIES ENVIRONMENT "SPINDRIFT_PLUGIN_PATH=${SPINDRIFT_PLUGIN_BUILD_DIR};OMP_NUM_THREADS=1;SPINDRIFT_DIR=${PROJECT_SOURCE_DIR}"
  TIMEOUT 300 SKIP_RETURN_CODE 77)
