# Animation (issue 10): keyframe channels, motion along paths, springs, kinematics, particles.
# Sources live in tests/anim/; every program links the scene library (where animation lives).
if(TARGET cj::scene)
  cj_add_test(test_anim_channels SOURCES anim/test_anim_channels.c LIBS cj::scene)
  cj_add_test(test_anim_path SOURCES anim/test_anim_path.c LIBS cj::scene)
  cj_add_test(test_springs SOURCES anim/test_springs.c LIBS cj::scene)
  cj_add_test(test_ik SOURCES anim/test_ik.c LIBS cj::scene)
  cj_add_test(test_particles SOURCES anim/test_particles.c LIBS cj::scene)
  cj_add_test(test_anim_scene SOURCES anim/test_anim_scene.c LIBS cj::scene)
  cj_add_test(test_anim_json SOURCES anim/test_anim_json.c LIBS cj::scene)
endif()
# Contract of `casteljau animate` (frames, checkpoints, bad input): runs the built tool.
if(TARGET casteljau AND CJ_WITH_OIIO)
  cj_add_test(test_cli_animate SOURCES anim/test_cli_animate.c)
  target_compile_definitions(test_cli_animate PRIVATE CJ_CLI="$<TARGET_FILE:casteljau>")
  add_dependencies(test_cli_animate casteljau)
endif()
