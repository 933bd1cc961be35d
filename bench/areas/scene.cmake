# bench_scene: loading the shipped scenes; JSON (inline mesh), OBJ and PLY read rates.
if(TARGET cj::scene)
  add_executable(bench_scene bench_scene.c)
  target_link_libraries(bench_scene PRIVATE cj::scene m)
  target_compile_definitions(bench_scene PRIVATE _POSIX_C_SOURCE=200809L
    CJ_TEAPOT_PATH="${PROJECT_SOURCE_DIR}/data/teapot.bpt" CJ_SCENES_DIR="${PROJECT_SOURCE_DIR}/scenes")
  cj_warnings(bench_scene)
endif()
