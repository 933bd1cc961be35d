# Issue 23: certified queries of curves (intersections, nearest points) against MPFR and
# long-double polyline oracles (tests/query/query_oracle.c, independent of the library).
add_library(cj_query_oracle STATIC ${CMAKE_CURRENT_SOURCE_DIR}/query/query_oracle.c)
target_link_libraries(cj_query_oracle PUBLIC cj_test_support PkgConfig::CJ_MPFR)
target_include_directories(cj_query_oracle PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/query)
cj_warnings(cj_query_oracle)
cj_add_test(test_intersect SOURCES query/test_intersect.c LIBS cj_query_oracle)
cj_add_test(test_nearest SOURCES query/test_nearest.c LIBS cj_query_oracle)
# Contract of `casteljau intersect` / `casteljau nearest`: runs the built tool.
cj_add_test(test_cli_query SOURCES query/test_cli_query.c)
target_compile_definitions(test_cli_query PRIVATE CJ_CLI="$<TARGET_FILE:casteljau>"
  CJ_QUERY_DOC="${PROJECT_SOURCE_DIR}/docs/queries_demo.json"
  CJ_TMP_DIR="${CMAKE_CURRENT_BINARY_DIR}")
if(CJ_WITH_OIIO AND TARGET cj::viz)
  target_compile_definitions(test_cli_query PRIVATE CJ_HAVE_PLOT=1)
endif()
add_dependencies(test_cli_query casteljau)
cj_add_test(test_offset SOURCES query/test_offset.c LIBS cj_query_oracle)
# Nearest point on Bézier patches (surfaces/): exact 256-bit grid distances against the bound.
cj_add_test(test_patch_nearest SOURCES query/test_patch_nearest.c LIBS cj::surfaces PkgConfig::CJ_MPFR)
# Plane sections of Bézier patches: exact circles (sphere, paraboloid) and a long-double line
# oracle on random patches (never missed: every crossing within the proven deviation).
cj_add_test(test_patch_section SOURCES query/test_patch_section.c LIBS cj::surfaces)
# Contract of `casteljau section` and `casteljau nearest` on patches: runs the built tool.
cj_add_test(test_cli_section SOURCES query/test_cli_section.c)
target_compile_definitions(test_cli_section PRIVATE CJ_CLI="$<TARGET_FILE:casteljau>"
  CJ_TMP_DIR="${CMAKE_CURRENT_BINARY_DIR}")
add_dependencies(test_cli_section casteljau)
# Trimmed offsets: a circle arc inwards past its radius vanishes, a parabola loses its
# swallowtail (long-double distance oracle), a loop-free offset comes back unchanged.
cj_add_test(test_offset_trim SOURCES query/test_offset_trim.c)
# Plane sections of models as joined cubic chains (cj_patches_section_curves): sphere octants,
# the teapot, a B-spline surface's patches, against long-double crossings and Newton projections.
cj_add_test(test_section_curves SOURCES query/test_section_curves.c LIBS cj::surfaces)
target_compile_definitions(test_section_curves PRIVATE CJ_TEAPOT_PATH="${PROJECT_SOURCE_DIR}/data/teapot.bpt")
if(CJ_WITH_OIIO AND TARGET cj::viz)
  target_compile_definitions(test_cli_section PRIVATE CJ_HAVE_PLOT=1)
endif()
# Stroke outlines (butt/round/square caps, closed curves) and offsets through a cusp, against the
# exact offsets and caps in long double, both ways.
cj_add_test(test_offset_outline SOURCES query/test_offset_outline.c)
# Adversarial intersections with exact answers known by construction (near-tangencies, a G1
# joint, coincident curves, a triple root, huge and tiny scales): ours must agree with the facts;
# OpenCASCADE (scripts/setup.sh installs it) runs beside and its answers are printed, not asserted.
cj_add_test(test_query_adversarial SOURCES query/test_query_adversarial.cpp)
find_path(CJ_OCCT_INCLUDE Geom2dAPI_InterCurveCurve.hxx PATH_SUFFIXES opencascade)
find_library(CJ_OCCT_TKGEOMALGO TKGeomAlgo)
find_library(CJ_OCCT_TKGEOMBASE TKGeomBase)
find_library(CJ_OCCT_TKG2D TKG2d)
find_library(CJ_OCCT_TKMATH TKMath)
find_library(CJ_OCCT_TKERNEL TKernel)
if(CJ_OCCT_INCLUDE AND CJ_OCCT_TKGEOMALGO AND CJ_OCCT_TKGEOMBASE AND CJ_OCCT_TKG2D AND
   CJ_OCCT_TKMATH AND CJ_OCCT_TKERNEL)
  target_include_directories(test_query_adversarial SYSTEM PRIVATE ${CJ_OCCT_INCLUDE})
  target_link_libraries(test_query_adversarial PRIVATE ${CJ_OCCT_TKGEOMALGO} ${CJ_OCCT_TKGEOMBASE}
    ${CJ_OCCT_TKG2D} ${CJ_OCCT_TKMATH} ${CJ_OCCT_TKERNEL})
  target_compile_definitions(test_query_adversarial PRIVATE CJ_HAVE_OCCT=1)
endif()
