# Camera model and exact triangle rasterizer (issue 8: "Camera and visibility", "Triangles,
# exactly"). The rasterizer's contract is private to raster/ (raster/src/raster3d_internal.h).
cj_add_test(test_camera SOURCES test_camera.c LIBS cj::scene)
