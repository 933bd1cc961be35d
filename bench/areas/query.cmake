# bench_query (issue 23): certified intersections, nearest points and offsets of cubics.
add_executable(bench_query ${CMAKE_CURRENT_SOURCE_DIR}/bench_query.c)
target_include_directories(bench_query PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
target_link_libraries(bench_query PRIVATE cj::curves)
target_compile_definitions(bench_query PRIVATE _POSIX_C_SOURCE=200809L)
cj_warnings(bench_query)
