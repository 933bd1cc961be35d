# The command-line tool in the user's hands (issue 25): progress, summary, --quiet, Ctrl-C,
# options, completion; and the default thread count (affinity, cgroup quota).
# Progress on a terminal, the summary line, --quiet, the large-work notice and Ctrl-C (issue 25).
if(CJ_WITH_OIIO AND TARGET cj::viz)
  cj_add_test(test_cli_progress SOURCES test_cli_progress.c)
  target_compile_definitions(test_cli_progress PRIVATE CJ_CLI="$<TARGET_FILE:casteljau>")
  add_dependencies(test_cli_progress casteljau)
endif()
# Options of every command: -h alone, "did you mean", usage completeness, the animate example.
if(CJ_WITH_OIIO AND TARGET cj::viz)
  cj_add_test(test_cli_options SOURCES test_cli_options.c)
  target_compile_definitions(test_cli_options PRIVATE CJ_CLI="$<TARGET_FILE:casteljau>"
    CJ_SCENES_DIR="${PROJECT_SOURCE_DIR}/scenes")
  add_dependencies(test_cli_options casteljau)
endif()
# The bash completion against the built tool (commands, each command's options).
add_test(NAME test_bash_completion COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/completion_check.sh
  ${PROJECT_SOURCE_DIR}/app/casteljau.bash-completion $<TARGET_FILE:casteljau>)
# The default thread count: affinity and cgroup v2 quota (raster/src/cpu_count.c, private).
cj_add_test(test_cpu_count SOURCES test_cpu_count.c LIBS cj::raster)
target_include_directories(test_cpu_count PRIVATE ${PROJECT_SOURCE_DIR}/raster/src)
