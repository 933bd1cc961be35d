# Incremental tessellation (issue 19): the cache against one-shot tessellation after random
# edit sequences (bit-identical meshes, incremental work, no cracks).
cj_add_test(test_tess_cache SOURCES test_tess_cache.c LIBS cj::surfaces)
target_compile_definitions(test_tess_cache PRIVATE CJ_TEAPOT_PATH="${PROJECT_SOURCE_DIR}/data/teapot.bpt")
# The renderer's cache: cached renders after control-point edits == one-shot renders.
cj_add_test(test_render_tess_cache SOURCES test_render_tess_cache.c LIBS cj::raster cj::scene)
target_include_directories(test_render_tess_cache PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
target_compile_definitions(test_render_tess_cache PRIVATE CJ_TEAPOT_PATH="${PROJECT_SOURCE_DIR}/data/teapot.bpt")
# Cancelling the cache's update and a cached render's preparation, then finishing: the same mesh
# and image as one-shot, no work lost.
cj_add_test(test_tess_cancel SOURCES test_tess_cancel.c LIBS cj::raster cj::scene cj::surfaces)
target_include_directories(test_tess_cancel PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
target_compile_definitions(test_tess_cancel PRIVATE CJ_TEAPOT_PATH="${PROJECT_SOURCE_DIR}/data/teapot.bpt")
# Planning's slab-table trial without triangles == the triangle-by-triangle trial, bit for bit.
cj_add_test(test_tess_trial SOURCES test_tess_trial.c LIBS cj::surfaces)
target_include_directories(test_tess_trial PRIVATE ${PROJECT_SOURCE_DIR}/surfaces/src ${PROJECT_SOURCE_DIR}/curves/src)
target_compile_definitions(test_tess_trial PRIVATE CJ_TEAPOT_PATH="${PROJECT_SOURCE_DIR}/data/teapot.bpt")
