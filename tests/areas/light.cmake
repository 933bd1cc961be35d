# Light and reflection (issue 21, docs/light.md): one reflection model in both renderers,
# checked against its closed form on an exact sphere, and the renderers against each other.
if(TARGET cj::raster)
  cj_add_test(test_light_agree SOURCES test_light_agree.c LIBS cj::raster cj::scene)
endif()
