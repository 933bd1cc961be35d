# Hardening (issue 14): failed writes lose nothing, bounded work, no inf printed, start-up cost,
# messages and first-contact behaviour of the casteljau tool.
if(CJ_WITH_OIIO AND TARGET cj::viz)
  # Formats by extension, float images, full-disk behaviour, plug-in loaded on first use.
  cj_add_test(test_image_write SOURCES test_image_write.c LIBS cj::viz)
endif()
