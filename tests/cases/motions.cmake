# Tutorials of moving walls (issue 38 items 4, 5): each run as a user runs it, then its own check
# script (tutorials/<case>/check*.py) on what it wrote (tutorialScript.sh). Measured values in the
# comments (docs/VALIDATION.md "Wave makers and rolling").
if(PVPYTHON)
  function(tutorial_script name tutorial edits script)
    add_test(NAME Tutorial.${name}
      COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/tutorialScript.sh $<TARGET_FILE:spindriftSolver>
              ${PROJECT_SOURCE_DIR}/tutorials/${tutorial} ${PVPYTHON} "${edits}" ${script} ${ARGN})
    set_tests_properties(Tutorial.${name} PROPERTIES
      ENVIRONMENT "${SPINDRIFT_CASE_TEST_ENV};SPINDRIFT_DIR=${PROJECT_SOURCE_DIR}" TIMEOUT 900 LABELS tutorial)
  endfunction()
endif()

if(PVPYTHON)
  # rollingTank3D, quick mode: Δx 0.02 instead of 0.015 and 2 s of 5 s (the roll ramped up over
  # the first second, then half a period): no particle lost or outside the rolling tank (the
  # nearest 0.46 Δx inside a face), volume within 0.02 %, the surface's forced slope in the tank's
  # frame 1.33 tan(roll) (linear sloshing's gain 1.53 at T = 2 s, T1 = 1.175 s), fit R² 0.993
  tutorial_script(rollingTank3D rollingTank3D
    "constant/fluidProperties:particleSpacing=0.02,system/controlDict:endTime=2" checkRolling.py --from 1)
endif()

if(PVPYTHON)
  # waveTank2D, quick mode: Δx 0.04 instead of 0.02 (H/Δx 2.5) and 12 s of 13, the first gauge
  # (2 wavelengths): period within 1 %, height 0.4-1.05 H (measured: 3 waves, T -0.45 %,
  # H 0.0595 m = -40 %; 132 s wall on 2 loaded cores; the full case at Δx 0.02: T -0.23 %, H -29 %)
  tutorial_script(waveTank2D waveTank2D
    "constant/fluidProperties:particleSpacing=0.04,system/controlDict:endTime=12" checkWaves.py
    --gauges 0 --height-range 0.4 1.05)
endif()
