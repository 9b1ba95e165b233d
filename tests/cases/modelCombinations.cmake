# Every model plugin of issue 3 (Perea & Cordero's four and the standard ones they compete
# with) swapped alone into the hydrostatic tank and the dam break, run briefly: the solver
# finishes, the fluid stays in the tank, the max density error stays below a bound (the
# foundation models reach 11.5 % in the tank and 9.6 % in the dam break in these runs: the
# start-up transient of a lattice released under gravity).
add_executable(spindriftFluidInBox ${CMAKE_CURRENT_LIST_DIR}/FluidInBox.cpp)
target_link_libraries(spindriftFluidInBox PRIVATE spindrift)

set(modelCombinationSwaps
  kernel:sinc2 kernel:poly6Spiky pressure:isobaric viscosity:pereaCordero viscosity:xsph
  integrator:velocityVerlet integrator:pereaCordero)
# tutorial, end time, max density error %, tank (xmin ymin xmax wallTop ceiling tolerance):
# the inner wall surfaces, the height of the (open-top) walls, a ceiling of twice that for
# spray, and half a particle spacing (a particle beyond it has passed the first wall layer)
set(modelCombinationCases
  "hydrostaticTank2D|0.2|18|0 0 0.2 0.4 0.8 0.005"
  "damBreak2D|0.04|18|0 0 0.40005 0.2286 0.4572 0.000714")

foreach(c ${modelCombinationCases})
  string(REPLACE "|" ";" fields "${c}")
  list(GET fields 0 tutorial)
  list(GET fields 1 endTime)
  list(GET fields 2 maxError)
  list(GET fields 3 boxText)
  separate_arguments(box UNIX_COMMAND "${boxText}")
  foreach(swap ${modelCombinationSwaps})
    string(REPLACE ":" ";" parts "${swap}")
    list(GET parts 0 kind)
    list(GET parts 1 type)
    set(name ModelCombination.${tutorial}.${kind}.${type})
    add_test(NAME ${name}
      COMMAND ${CMAKE_CURRENT_LIST_DIR}/modelCombination.sh $<TARGET_FILE:spindriftSolver>
              $<TARGET_FILE:spindriftFluidInBox> ${PROJECT_SOURCE_DIR}/tutorials/${tutorial}
              ${kind} ${type} ${endTime} ${maxError} ${box})
    set_tests_properties(${name} PROPERTIES ENVIRONMENT "${SPINDRIFT_CASE_TEST_ENV}" TIMEOUT 300)
  endforeach()
endforeach()

# The tutorial of Perea & Cordero's wave (all four seed models), shortened to its first 0.02 s.
add_test(NAME ModelCombination.pereaWave.seedModels
  COMMAND ${CMAKE_CURRENT_LIST_DIR}/modelCombination.sh $<TARGET_FILE:spindriftSolver>
          $<TARGET_FILE:spindriftFluidInBox> ${PROJECT_SOURCE_DIR}/tutorials/pereaWave
          none seedModels 0.02 18 0 0 1.03 0.5 1.0 0.0025)
set_tests_properties(ModelCombination.pereaWave.seedModels PROPERTIES ENVIRONMENT "${SPINDRIFT_CASE_TEST_ENV}" TIMEOUT 300)
