# bench_anim: integrators' error vs time step and time per step on a damped oscillator and a
# large-amplitude pendulum (exact references), instability steps, log-log plot to a PNG.
if(TARGET cj::scene AND TARGET cj::raster AND TARGET cj::viz)
  add_executable(bench_anim bench_anim.c)
  target_link_libraries(bench_anim PRIVATE cj::scene cj::raster cj::viz m)
  target_compile_definitions(bench_anim PRIVATE _POSIX_C_SOURCE=200809L)
  cj_warnings(bench_anim)
endif()
