# bench_startup: wall time and peak memory of 100 launches of the casteljau tool per command
# (the commands that write no image must not load OpenImageIO).
add_executable(bench_startup ${CMAKE_CURRENT_SOURCE_DIR}/bench_startup.c)
target_include_directories(bench_startup PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
target_compile_definitions(bench_startup PRIVATE CJ_CLI="$<TARGET_FILE:casteljau>")
add_dependencies(bench_startup casteljau)
cj_warnings(bench_startup)
