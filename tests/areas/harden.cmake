# Hardening (issue 14): failed writes lose nothing, bounded work, no inf printed, start-up cost,
# messages and first-contact behaviour of the casteljau tool.
if(CJ_WITH_OIIO AND TARGET cj::viz)
  # Formats by extension, float images, full-disk behaviour, plug-in loaded on first use.
  cj_add_test(test_image_write SOURCES test_image_write.c LIBS cj::viz)
endif()
# The tool under hostile and first-contact use: option syntax, --help/--version, stdin,
# one-line messages, never inf, bounded contour work, start-up without OpenImageIO.
cj_add_test(test_cli_harden SOURCES test_cli_harden.c)
target_compile_definitions(test_cli_harden PRIVATE CJ_CLI="$<TARGET_FILE:casteljau>"
  CJ_VERSION="${PROJECT_VERSION}")
add_dependencies(test_cli_harden casteljau)
# The README's "$ command" transcripts, run and compared (they went stale once).
cj_add_test(test_readme_examples SOURCES test_readme_examples.c)
target_compile_definitions(test_readme_examples PRIVATE CJ_CLI="$<TARGET_FILE:casteljau>"
  CJ_README="${PROJECT_SOURCE_DIR}/README.md")
add_dependencies(test_readme_examples casteljau)
