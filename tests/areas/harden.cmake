# Hardening (issue 14): failed writes lose nothing, bounded work, no inf printed, start-up cost,
# messages and first-contact behaviour of the casteljau tool.
if(CJ_WITH_OIIO AND TARGET cj::viz)
  # Formats by extension, float images, full-disk behaviour, plug-in loaded on first use.
  cj_add_test(test_image_write SOURCES test_image_write.c LIBS cj::viz)
endif()
# The tool under hostile and first-contact use: option syntax, --help/--version, stdin,
# one-line messages, never inf, bounded contour work, start-up without OpenImageIO.
# test_cli_harden_files: full disk for every writer, tessellate and plot first contact.
foreach(g 1 2)
  set(t test_cli_harden)
  if(g EQUAL 2)
    set(t test_cli_harden_files)
  endif()
  cj_add_test(${t} SOURCES test_cli_harden.c)
  target_compile_definitions(${t} PRIVATE CJ_CLI="$<TARGET_FILE:casteljau>"
    CJ_VERSION="${PROJECT_VERSION}" CJ_HARDEN_GROUP=${g})
  add_dependencies(${t} casteljau)
endforeach()
# The README's "$ command" transcripts, run and compared (they went stale once).
cj_add_test(test_readme_examples SOURCES test_readme_examples.c)
target_compile_definitions(test_readme_examples PRIVATE CJ_CLI="$<TARGET_FILE:casteljau>"
  CJ_README="${PROJECT_SOURCE_DIR}/README.md")
add_dependencies(test_readme_examples casteljau)
# find_package(casteljau) straight from this build tree (exported targets, no install).
set(cj_bt_flags)
if(CJ_SANITIZE)
  set(cj_bt_flags "-fsanitize=address,undefined")
endif()
add_test(NAME test_build_tree_package COMMAND ${CMAKE_COMMAND}
  -DCJ_BUILD_DIR=${PROJECT_BINARY_DIR} -DCJ_WORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/build_tree_consumer
  -DCJ_CONSUMER_DIR=${CMAKE_CURRENT_SOURCE_DIR}/install/consumer
  -DCJ_C_COMPILER=${CMAKE_C_COMPILER} -DCJ_CXX_COMPILER=${CMAKE_CXX_COMPILER}
  -DCJ_GENERATOR=${CMAKE_GENERATOR} "-DCJ_EXTRA_FLAGS=${cj_bt_flags}"
  -P ${CMAKE_CURRENT_SOURCE_DIR}/build_tree_package.cmake)
set_tests_properties(test_build_tree_package PROPERTIES TIMEOUT 300)
# Library side: CJ_ERR_RANGE on overflow, contour tolerance floor, tessellation size prediction,
# degenerate patches, plot title cap and tick computation over the whole double range.
if(TARGET cj::raster)
  cj_add_test(test_harden_lib SOURCES test_harden_lib.c LIBS cj::surfaces cj::raster cj::scene m)
  # issue 24: the shared reader and atomic writer (curves/src/file_internal.h)
  target_include_directories(test_harden_lib PRIVATE ${PROJECT_SOURCE_DIR}/curves/src)
  target_compile_definitions(test_harden_lib PRIVATE
    CJ_TEAPOT_PATH="${PROJECT_SOURCE_DIR}/data/teapot.bpt")
endif()
# An installed casteljau, moved to another prefix, finds its teapot and image plug-in.
add_test(NAME test_installed_tool COMMAND ${CMAKE_COMMAND}
  -DCJ_BUILD_DIR=${PROJECT_BINARY_DIR} -DCJ_WORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/installed_tool
  -DCJ_LIBDIR=${CMAKE_INSTALL_LIBDIR} -DCJ_CONFIG=$<CONFIG>
  -P ${CMAKE_CURRENT_SOURCE_DIR}/installed_tool.cmake)
set_tests_properties(test_installed_tool PROPERTIES TIMEOUT 300 RESOURCE_LOCK cj_install)
# Issue 24, hostile input to the newer parts (test_cli_hostile.c, two halves): devices and huge
# images refused, simulation parameters bounded before the first frame, checkpoints checked,
# render and trace validate alike, outputs that are inputs refused, destinations checked first,
# interrupted GIFs leave nothing, and the exit-code contract of every command.
if(TARGET cj::scene AND CJ_WITH_OIIO)
  foreach(g 1 2)
    set(t test_cli_hostile_${g})
    cj_add_test(${t} SOURCES test_cli_hostile.c)
    target_compile_definitions(${t} PRIVATE CJ_CLI="$<TARGET_FILE:casteljau>"
      CJ_SCENES="${PROJECT_SOURCE_DIR}/scenes" CJ_HOSTILE_GROUP=${g})
    add_dependencies(${t} casteljau)
    set_tests_properties(${t} PROPERTIES TIMEOUT 600)
  endforeach()
endif()
