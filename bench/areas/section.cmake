# bench_section (issue 23): the teapot's plane section as joined cubic curves, stroke outlines
# of cubics, the nearest point on an equidistant patch.
add_executable(bench_section ${CMAKE_CURRENT_SOURCE_DIR}/bench_section.c)
target_include_directories(bench_section PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
target_link_libraries(bench_section PRIVATE cj::curves cj::surfaces)
target_compile_definitions(bench_section PRIVATE _POSIX_C_SOURCE=200809L
  CJ_TEAPOT_PATH="${PROJECT_SOURCE_DIR}/data/teapot.bpt")
cj_warnings(bench_section)
