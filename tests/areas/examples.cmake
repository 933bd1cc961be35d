# examples/ (issue 25): each program runs and its output is checked (tests/run_example.cmake).
function(cj_example_test name)
  cmake_parse_arguments(E "" "" "ARGS;EXPECT;FILES" ${ARGN})
  add_test(NAME test_example_${name}
    COMMAND ${CMAKE_COMMAND} -DEXE=$<TARGET_FILE:example_${name}> "-DARGS=${E_ARGS}"
            -DWORKDIR=${CMAKE_CURRENT_BINARY_DIR}/example_${name} "-DEXPECT=${E_EXPECT}"
            "-DFILES=${E_FILES}" -P ${PROJECT_SOURCE_DIR}/tests/run_example.cmake)
endfunction()
if(TARGET example_curve_flatten)
  # The midpoint of the cubic (0,0) (1,2) (3,2) (4,0) is exactly (2, 1.5); flattening at 1e-3
  # must end at the last control point.
  cj_example_test(curve_flatten
    EXPECT "c\\(0.5\\) = \\(2, 1.5\\)" "distance to the curve at most [0-9.e-]+ \\(asked 1e-3\\)"
           "asked 1e-3[)].0[.]000000 0[.]000000." "4[.]000000 0[.]000000.?$")
endif()
if(TARGET example_render_scene)
  cj_example_test(render_scene ARGS scene.png
    EXPECT "wrote scene.png \\(320 x 240, 3 objects\\)" FILES scene.png)
endif()
if(TARGET example_animate_frames)
  # The ball starts left of centre (column < 60 of 160) and ends right of it (> 100).
  cj_example_test(animate_frames ARGS ball 4
    EXPECT "frame 0 t=0.000 ball pixels [1-9][0-9]* mean column [1-5]?[0-9]\\.[0-9] "
           "frame 3 t=1.000 ball pixels [1-9][0-9]* mean column 1[0-5][0-9]\\.[0-9] "
    FILES ball_000.png ball_001.png ball_002.png ball_003.png)
endif()
