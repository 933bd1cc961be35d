# cmake -DEXE=... -DARGS="a;b" -DWORKDIR=... -DEXPECT="regex;regex" -DFILES="f1;f2" -P run_example.cmake
# Runs one example program: it must exit 0, its output must match every EXPECT regex (each
# printed as checked), and every file in FILES (relative to WORKDIR) must exist, non-empty.
file(REMOVE_RECURSE ${WORKDIR})
file(MAKE_DIRECTORY ${WORKDIR})
execute_process(COMMAND ${EXE} ${ARGS} WORKING_DIRECTORY ${WORKDIR}
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${EXE} exited with ${rc}")
endif()
foreach(re IN LISTS EXPECT)
  if(NOT out MATCHES "${re}")
    message(FATAL_ERROR "output does not match: ${re}")
  endif()
  message("checked: output matches ${re}")
endforeach()
foreach(f IN LISTS FILES)
  file(SIZE ${WORKDIR}/${f} size)
  if(NOT size GREATER 0)
    message(FATAL_ERROR "${f} is missing or empty")
  endif()
  message("checked: ${f} written (${size} bytes)")
endforeach()
