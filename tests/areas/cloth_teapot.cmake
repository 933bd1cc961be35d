# The shipped cloth-on-teapot animation (issue 25): no cloth particle ends inside the teapot.
if(TARGET cj::scene)
  cj_add_test(test_cloth_teapot SOURCES anim/test_cloth_teapot.c LIBS cj::scene)
  target_compile_definitions(test_cloth_teapot PRIVATE CJ_SCENES_DIR="${PROJECT_SOURCE_DIR}/scenes"
                            CJ_TEAPOT_PATH="${PROJECT_SOURCE_DIR}/data/teapot.bpt")
endif()
