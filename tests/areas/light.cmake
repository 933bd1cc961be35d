# Light and reflection (issue 21, docs/light.md): one reflection model in both renderers,
# checked against its closed form on an exact sphere, and the renderers against each other.
if(TARGET cj::raster)
  cj_add_test(test_light_agree SOURCES test_light_agree.c LIBS cj::raster cj::scene)
endif()
# Radiometric lights against closed forms: inverse square, directional irradiance, a rectangular
# emitter's form factor (both renderers), one-sided emitters, legacy unchanged.
if(TARGET cj::raster)
  cj_add_test(test_light_radiometric SOURCES test_light_radiometric.c support/light_floor.c LIBS cj::raster cj::scene)
endif()
# EXR output: 32-bit float by default, half on request, no infinity ever written.
if(CJ_WITH_OIIO AND TARGET cj::viz)
  pkg_check_modules(CJ_LIGHT_OIIO REQUIRED IMPORTED_TARGET OpenImageIO)
  cj_add_test(test_light_exr SOURCES test_light_exr.cpp LIBS cj::viz PkgConfig::CJ_LIGHT_OIIO)
endif()
# BRDFs (raster/src/brdf.h, private): Fresnel closed forms, energy conservation, sampling.
if(TARGET cj::raster)
  cj_add_test(test_light_brdf SOURCES test_light_brdf.c LIBS cj::raster)
  target_include_directories(test_light_brdf PRIVATE ${PROJECT_SOURCE_DIR}/raster/src)
endif()
# The path tracer: furnace, NEE + MIS against the form factor, emitters seen by camera rays,
# RMSE against spp, thread invariance.
if(TARGET cj::raster)
  cj_add_test(test_light_path SOURCES test_light_path.c support/light_floor.c LIBS cj::raster cj::scene)
endif()
# The thin lens: circle of confusion against its formula.
if(TARGET cj::raster)
  cj_add_test(test_light_lens SOURCES test_light_lens.c LIBS cj::raster cj::scene)
endif()
# Pixel reconstruction filters: edge responses against the filters' definitions.
if(TARGET cj::raster)
  cj_add_test(test_light_filter SOURCES test_light_filter.c LIBS cj::raster cj::scene)
endif()
# Motion blur: a square sliding under a box shutter against the exact ramp of coverage.
if(TARGET cj::raster)
  cj_add_test(test_light_motion SOURCES test_light_motion.c LIBS cj::raster cj::scene)
endif()
# Disc and sphere emitters against their closed-form irradiance, in every renderer.
if(TARGET cj::raster)
  cj_add_test(test_light_emitters SOURCES test_light_emitters.c support/light_floor.c LIBS cj::raster cj::scene)
endif()
# Emissive surfaces sampled as lights by the path tracer: against the form factor, and the
# variance drop against finding them by chance.
if(TARGET cj::raster)
  cj_add_test(test_light_emissive SOURCES test_light_emissive.c LIBS cj::raster cj::scene)
endif()
