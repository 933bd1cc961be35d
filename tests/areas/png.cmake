# PNG through libpng (issue 20's start-up row): the libpng encoder and decoder against the
# OpenImageIO plug-in they replaced for PNG, pixel for pixel, and their error paths.
if(CJ_WITH_OIIO AND TARGET cj::viz AND TARGET casteljau_image_oiio)
  pkg_check_modules(CJ_TEST_PNG REQUIRED IMPORTED_TARGET libpng zlib)
  # image_png.c is compiled in (its functions are private to the library).
  cj_add_test(test_image_png SOURCES test_image_png.c ${PROJECT_SOURCE_DIR}/viz/src/image_png.c
    LIBS PkgConfig::CJ_TEST_PNG cmocka ${CMAKE_DL_LIBS})
  target_include_directories(test_image_png PRIVATE ${PROJECT_SOURCE_DIR}/viz/src
    ${PROJECT_SOURCE_DIR}/viz/include ${PROJECT_SOURCE_DIR}/curves/include)
  target_compile_definitions(test_image_png PRIVATE
    CJ_TEST_OIIO_PLUGIN="$<TARGET_FILE:casteljau_image_oiio>")
  add_dependencies(test_image_png casteljau_image_oiio)
endif()
# An unknown command suggests the nearest (the option suggester's rule, app/cli_common.c).
if(TARGET casteljau)
  cj_add_test(test_cli_commands SOURCES test_cli_commands.c)
  target_include_directories(test_cli_commands PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_compile_definitions(test_cli_commands PRIVATE CJ_CLI="$<TARGET_FILE:casteljau>")
  add_dependencies(test_cli_commands casteljau)
endif()
# The default font through fontconfig, and the message when there is none.
if(TARGET casteljau AND TARGET cj::raster)
  cj_add_test(test_font_lookup SOURCES test_font_lookup.c LIBS cj::raster)
  target_include_directories(test_font_lookup PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_compile_definitions(test_font_lookup PRIVATE CJ_CLI="$<TARGET_FILE:casteljau>")
  add_dependencies(test_font_lookup casteljau)
endif()
# What the program maps at start-up: no GLFW/OpenGL, FFmpeg or OpenImageIO (modules instead).
if(TARGET casteljau AND CJ_HAVE_VIDEO)
  cj_add_test(test_cli_modules SOURCES test_cli_modules.c)
  target_include_directories(test_cli_modules PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_compile_definitions(test_cli_modules PRIVATE CJ_CLI="$<TARGET_FILE:casteljau>"
    CJ_ANIM_PATH="${PROJECT_SOURCE_DIR}/scenes/anim_flyby.json")
  add_dependencies(test_cli_modules casteljau)
endif()
