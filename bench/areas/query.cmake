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
  add_executable(bench_query_occt ${CMAKE_CURRENT_SOURCE_DIR}/bench_query_occt.cpp
    ${CMAKE_CURRENT_SOURCE_DIR}/bench_query_offset_peer.cpp)
  target_include_directories(bench_query_occt PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_include_directories(bench_query_occt SYSTEM PRIVATE ${CJ_OCCT_INCLUDE})
  target_link_libraries(bench_query_occt PRIVATE cj::curves ${CJ_OCCT_TKGEOMALGO}
    ${CJ_OCCT_TKGEOMBASE} ${CJ_OCCT_TKG2D} ${CJ_OCCT_TKMATH} ${CJ_OCCT_TKERNEL})
  target_compile_definitions(bench_query_occt PRIVATE _POSIX_C_SOURCE=200809L)
  # kurbo in the same process: the static library of bench/kurbo (flatten.cmake builds it).
  if(TARGET cj_bench_kurbo)
    target_link_libraries(bench_query_occt PRIVATE cj_bench_kurbo pthread dl m)
    target_compile_definitions(bench_query_occt PRIVATE CJ_HAVE_KURBO=1)
  endif()
else()
  message(STATUS "OpenCASCADE not found: bench_query_occt is not built")
endif()
