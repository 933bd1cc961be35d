# bench_query (issue 23): certified intersections, nearest points and offsets of cubics.
add_executable(bench_query ${CMAKE_CURRENT_SOURCE_DIR}/bench_query.c)
target_include_directories(bench_query PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
target_link_libraries(bench_query PRIVATE cj::curves)
target_compile_definitions(bench_query PRIVATE _POSIX_C_SOURCE=200809L)
cj_warnings(bench_query)
# OpenCASCADE (Debian libocct-*-dev) in the same run: bench_query_occt links it; the library
# never does.
find_path(CJ_OCCT_INCLUDE Geom2dAPI_InterCurveCurve.hxx PATH_SUFFIXES opencascade)
find_library(CJ_OCCT_TKGEOMALGO TKGeomAlgo)
find_library(CJ_OCCT_TKGEOMBASE TKGeomBase)
find_library(CJ_OCCT_TKG2D TKG2d)
find_library(CJ_OCCT_TKMATH TKMath)
find_library(CJ_OCCT_TKERNEL TKernel)
if(CJ_OCCT_INCLUDE AND CJ_OCCT_TKGEOMALGO AND CJ_OCCT_TKGEOMBASE AND CJ_OCCT_TKG2D AND
   CJ_OCCT_TKMATH AND CJ_OCCT_TKERNEL)
  add_executable(bench_query_occt ${CMAKE_CURRENT_SOURCE_DIR}/bench_query_occt.cpp)
  target_include_directories(bench_query_occt PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_include_directories(bench_query_occt SYSTEM PRIVATE ${CJ_OCCT_INCLUDE})
  target_link_libraries(bench_query_occt PRIVATE cj::curves ${CJ_OCCT_TKGEOMALGO}
    ${CJ_OCCT_TKGEOMBASE} ${CJ_OCCT_TKG2D} ${CJ_OCCT_TKMATH} ${CJ_OCCT_TKERNEL})
  target_compile_definitions(bench_query_occt PRIVATE _POSIX_C_SOURCE=200809L)
else()
  message(STATUS "OpenCASCADE not found: bench_query_occt is not built")
endif()
# kurbo (Debian librust-kurbo-dev) on the same cubics and points: a cargo project built offline
# against /usr/share/cargo/registry (bench/kurbo_query/.cargo/config.toml). Not part of `all`:
#   cmake --build build --target bench_query_kurbo && build/bench/kurbo_query/release/kurbo_query
find_program(CJ_CARGO cargo)
if(CJ_CARGO)
  add_custom_target(bench_query_kurbo
    COMMAND ${CMAKE_COMMAND} -E env CARGO_TARGET_DIR=${CMAKE_CURRENT_BINARY_DIR}/kurbo_query
      ${CJ_CARGO} build --offline --release --quiet
    WORKING_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/kurbo_query
    COMMENT "cargo build --offline: kurbo_query")
endif()
