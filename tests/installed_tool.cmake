# CTest script (cmake -P): installs the build into a prefix, MOVES the prefix elsewhere, and
# runs the installed casteljau from there: it must find its teapot (<bindir>/../share) and its
# OpenImageIO plug-in, vector plot and viewer modules (<bindir>/../<libdir>/casteljau, checked with
# LD_DEBUG=libs) relative to itself. Inputs (-D): CJ_BUILD_DIR CJ_WORK_DIR CJ_LIBDIR CJ_CONFIG.
cmake_minimum_required(VERSION 3.20)
file(REMOVE_RECURSE ${CJ_WORK_DIR})
file(MAKE_DIRECTORY ${CJ_WORK_DIR})
set(cfg_args)
if(CJ_CONFIG)
  set(cfg_args --config ${CJ_CONFIG})
endif()
function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err
    WORKING_DIRECTORY ${CJ_WORK_DIR})
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}\n${err}")
  endif()
  set(run_out "${out}" PARENT_SCOPE)
  set(run_err "${err}" PARENT_SCOPE)
endfunction()
run("cmake --install" ${CMAKE_COMMAND} --install ${CJ_BUILD_DIR} --prefix ${CJ_WORK_DIR}/prefix
    ${cfg_args})
file(RENAME ${CJ_WORK_DIR}/prefix ${CJ_WORK_DIR}/moved)
set(exe ${CJ_WORK_DIR}/moved/bin/casteljau)
run("installed tessellate --teapot" ${exe} tessellate --teapot --uniform 2 -o t.obj)
if(NOT run_out MATCHES "patches 32")
  message(FATAL_ERROR "installed tessellate printed:\n${run_out}")
endif()
# TIFF: PNG goes through libpng and needs no plug-in.
run("installed plot" ${CMAKE_COMMAND} -E env LD_DEBUG=libs ${exe} plot --demo --width 120
    --height 90 -o g.tif)
string(REGEX MATCH "[^ \n]*libcasteljau_image_oiio.so" plugin "${run_err}")
if(NOT plugin MATCHES "^${CJ_WORK_DIR}/moved/")
  message(FATAL_ERROR "the installed plot did not load the moved plug-in (loaded: '${plugin}')")
endif()
message(STATUS "moved installation: teapot found, plug-in loaded from ${plugin}")
# The vector plot module (cairo), when built: an SVG loads it from the moved prefix.
if(EXISTS ${CJ_BUILD_DIR}/libcasteljau_cairo.so)
  run("installed plot to SVG" ${CMAKE_COMMAND} -E env LD_DEBUG=libs ${exe} plot --demo
      --width 120 --height 90 -o g.svg)
  string(REGEX MATCH "[^ \n]*libcasteljau_cairo.so" cairo "${run_err}")
  if(NOT cairo MATCHES "^${CJ_WORK_DIR}/moved/")
    message(FATAL_ERROR "the installed plot did not load the moved cairo module ('${cairo}')")
  endif()
  message(STATUS "moved installation: vector plot module loaded from ${cairo}")
endif()
# The viewer module (<libdir>/casteljau/libcasteljau_viewer.so), when built: `view` without a
# display fails, but only after loading the module from the moved prefix.
if(EXISTS ${CJ_BUILD_DIR}/libcasteljau_viewer.so)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=DISPLAY LD_DEBUG=libs ${exe} view
    --teapot RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err
    WORKING_DIRECTORY ${CJ_WORK_DIR})
  string(REGEX MATCH "[^ \n]*libcasteljau_viewer.so" viewer "${err}")
  if(NOT viewer MATCHES "^${CJ_WORK_DIR}/moved/" OR NOT err MATCHES "no display")
    message(FATAL_ERROR "the installed view did not load the moved module (loaded: '${viewer}')")
  endif()
  message(STATUS "moved installation: viewer module loaded from ${viewer}")
endif()
