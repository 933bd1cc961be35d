# Films (FFmpeg) and dithered GIFs (libimagequant) of `casteljau animate` (issue 25): decoded back.
if(TARGET casteljau AND CJ_WITH_OIIO AND CJ_HAVE_VIDEO)
  pkg_check_modules(CJ_TEST_AV REQUIRED IMPORTED_TARGET libavformat libavcodec libswscale libavutil)
  find_library(CJ_TEST_GIF_LIBRARY gif REQUIRED)
  cj_add_test(test_anim_video SOURCES anim/test_anim_video.c
    LIBS cj::viz PkgConfig::CJ_TEST_AV ${CJ_TEST_GIF_LIBRARY})
  target_compile_definitions(test_anim_video PRIVATE CJ_CLI="$<TARGET_FILE:casteljau>")
  add_dependencies(test_anim_video casteljau)
endif()
