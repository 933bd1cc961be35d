# CTest script (cmake -P): installs the build tree into a temporary prefix (not
# CMAKE_INSTALL_PREFIX, so the installed package must be relocatable), then, with nothing but
# that prefix:
#  1. the installed files: shared libraries with their SONAME links, headers, one .pc file per
#     module, the CMake package, man pages, bash completion, scenes/textures/teapot;
#  2. find_package: a separate project (consumer/) asking for curves alone (it must look for
#     nothing else), and again for every component, builds examples/ and one tiny program per
#     component; each runs;
#  3. pkg-config: the same programs compiled by a plain compiler call with
#     `pkg-config --cflags --libs casteljau-<component>` (shared libraries: no --static);
#  4. ldd: the installed casteljau resolves every library, ours from the prefix and no VTK;
#     a curves-only program needs no libGL, X11, GLFW, VTK, expat, LZ4 or LZMA;
#  5. `man -l` renders an installed page, and the installed bash completion completes; 6. `import casteljau` from the installed tree loads
#     the installed libraries and finds the installed teapot; 7. the installed tool renders a
#     shipped scene (its texture found relative to the scene).
#
# Inputs (-D): CJ_BUILD_DIR CJ_WORK_DIR CJ_CONSUMER_DIR CJ_EXAMPLES_DIR CJ_LIBDIR CJ_DATADIR
#              CJ_MANDIR CJ_C_COMPILER CJ_GENERATOR CJ_CONFIG CJ_EXTRA_FLAGS CJ_SOVERSION
#              CJ_MODULES CJ_PYTHON (empty: no Python module) CJ_PYTHON_DIR CJ_SHARED
#              CJ_COMPLETION_CHECK (tests/completion_check.sh)
cmake_minimum_required(VERSION 3.20)
foreach(v CJ_BUILD_DIR CJ_WORK_DIR CJ_CONSUMER_DIR CJ_EXAMPLES_DIR CJ_LIBDIR CJ_DATADIR
          CJ_MANDIR CJ_C_COMPILER CJ_GENERATOR CJ_MODULES)
  if(NOT DEFINED ${v} OR "${${v}}" STREQUAL "")
    message(FATAL_ERROR "run_install_test.cmake: ${v} is not set")
  endif()
endforeach()
set(prefix ${CJ_WORK_DIR}/prefix)
set(libdir ${prefix}/${CJ_LIBDIR})
file(REMOVE_RECURSE ${CJ_WORK_DIR})
file(MAKE_DIRECTORY ${CJ_WORK_DIR})
# Nothing of the build tree may leak in through the environment.
unset(ENV{LD_LIBRARY_PATH})
unset(ENV{PYTHONPATH})
unset(ENV{CJ_IMAGE_PLUGIN})

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err
    WORKING_DIRECTORY ${CJ_WORK_DIR})
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${ARGN}\n${out}\n${err}")
  endif()
  set(run_out "${out}" PARENT_SCOPE)
endfunction()
function(expect what text regex)
  if(NOT text MATCHES "${regex}")
    message(FATAL_ERROR "${what} printed:\n${text}\nexpected to match: ${regex}")
  endif()
endfunction()

# ---- 1. install ----
set(cfg_args)
if(CJ_CONFIG)
  set(cfg_args --config ${CJ_CONFIG})
endif()
run("cmake --install" ${CMAKE_COMMAND} --install ${CJ_BUILD_DIR} --prefix ${prefix} ${cfg_args})
set(want include/casteljau/bezier.h include/casteljau/transform.h
  ${CJ_LIBDIR}/cmake/casteljau/casteljauConfig.cmake
  ${CJ_LIBDIR}/cmake/casteljau/casteljauConfigVersion.cmake ${CJ_LIBDIR}/pkgconfig/casteljau.pc
  ${CJ_DATADIR}/casteljau/teapot.bpt ${CJ_DATADIR}/casteljau/scenes/teapot.json
  ${CJ_DATADIR}/casteljau/scenes/textures/porcelain.png
  ${CJ_DATADIR}/bash-completion/completions/casteljau
  ${CJ_MANDIR}/man1/casteljau.1 ${CJ_MANDIR}/man1/casteljau-render.1)
foreach(m IN LISTS CJ_MODULES)
  list(APPEND want ${CJ_LIBDIR}/pkgconfig/casteljau-${m}.pc)
  if(CJ_SHARED)
    list(APPEND want ${CJ_LIBDIR}/libcasteljau_${m}.so ${CJ_LIBDIR}/libcasteljau_${m}.so.${CJ_SOVERSION})
  else()
    list(APPEND want ${CJ_LIBDIR}/libcasteljau_${m}.a)
  endif()
endforeach()
foreach(f IN LISTS want)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "installed tree lacks ${f}")
  endif()
endforeach()
file(GLOB headers ${prefix}/include/casteljau/*.h)
file(GLOB pages ${prefix}/${CJ_MANDIR}/man1/*.1)
list(LENGTH headers nheaders)
list(LENGTH pages npages)
message(STATUS "installed: ${nheaders} headers, ${npages} man pages, modules ${CJ_MODULES}")

# ---- 2. find_package consumers: curves alone, then every component ----
set(flag_args)
if(CJ_EXTRA_FLAGS)
  set(flag_args "-DCMAKE_C_FLAGS=${CJ_EXTRA_FLAGS}"
    "-DCMAKE_EXE_LINKER_FLAGS=${CJ_EXTRA_FLAGS} ${CJ_EXTRA_LINK_FLAGS}")
endif()
set(all_parts ${CJ_MODULES})
list(REMOVE_ITEM all_parts vtk) # (its programs need a display; the cross-check tests cover it)
# formats/ is installed because viz links it, but it has no public headers: nothing to program
list(REMOVE_ITEM all_parts formats)
set(sets curves)
if(NOT all_parts STREQUAL "curves")
  list(APPEND sets all)
endif()
foreach(set IN LISTS sets)
  set(parts curves)
  if(set STREQUAL "all")
    set(parts ${all_parts})
  endif()
  string(REPLACE ";" "\\;" parts_arg "${parts}")
  set(dir ${CJ_WORK_DIR}/cmake-${set})
  run("configuring the find_package consumer (${parts})" ${CMAKE_COMMAND} -S ${CJ_CONSUMER_DIR}
    -B ${dir} -G ${CJ_GENERATOR} -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_C_COMPILER=${CJ_C_COMPILER} "-DCJ_COMPONENTS=${parts_arg}"
    -DCJ_EXAMPLES_DIR=${CJ_EXAMPLES_DIR} ${flag_args})
  if(set STREQUAL "curves")
    expect("find_package(casteljau COMPONENTS curves)" "${run_out}" "curves alone: no other")
  endif()
  run("building the find_package consumer (${parts})" ${CMAKE_COMMAND} --build ${dir} -j 2)
endforeach()

# The programs and what each must print; run from both builds.
set(expect_consumer "casteljau consumer: c\\(0\\.5\\) = 1 1, bbox 0 0 2 1, moved 11 21, status: parameter out of range")
set(expect_curve_flatten "c\\(0.5\\) = \\(2, 1.5\\)")
set(expect_surfaces "S\\(0.5,0.5\\) = 0.5 0.5 0.25")
set(expect_scene "1 light, 0 nodes")
set(expect_raster "pixel \\(7,3\\) = 10 20 30 255")
set(expect_viz "2x2 read back identical")
set(expect_render_scene "wrote scene.png \\(320 x 240, 3 objects\\)")
set(expect_animate_frames "frame 3 t=1.000 ball pixels [1-9]")
function(run_program what exe key)
  set(args)
  if(key STREQUAL "render_scene")
    set(args scene.png)
  elseif(key STREQUAL "animate_frames")
    set(args ball 4)
  elseif(key STREQUAL "viz")
    set(args viz.png)
  endif()
  run("${what}" ${exe} ${args})
  expect("${what}" "${run_out}" "${expect_${key}}")
endfunction()
set(nprog 0)
foreach(set IN LISTS sets)
  set(dir ${CJ_WORK_DIR}/cmake-${set})
  run_program("find_package consumer" ${dir}/consumer consumer)
  run_program("find_package example curve_flatten" ${dir}/example_curve_flatten curve_flatten)
  math(EXPR nprog "${nprog} + 2")
  if(set STREQUAL "all")
    foreach(c IN LISTS all_parts)
      if(NOT c STREQUAL "curves")
        run_program("find_package component ${c}" ${dir}/component_${c} ${c})
        math(EXPR nprog "${nprog} + 1")
      endif()
    endforeach()
    if("viz" IN_LIST all_parts)
      foreach(ex render_scene animate_frames)
        run_program("find_package example ${ex}" ${dir}/example_${ex} ${ex})
        math(EXPR nprog "${nprog} + 1")
      endforeach()
    endif()
  endif()
endforeach()
message(STATUS "find_package: ${nprog} programs built and run (curves alone, then ${all_parts})")

# ---- 3. pkg-config: a plain compiler call per program ----
find_program(PKG_CONFIG_EXECUTABLE NAMES pkg-config pkgconf REQUIRED)
set(ENV{PKG_CONFIG_PATH} ${libdir}/pkgconfig)
run("pkg-config --variable=pkgdatadir" ${PKG_CONFIG_EXECUTABLE} --variable=pkgdatadir casteljau-curves)
string(STRIP "${run_out}" pkgdatadir)
file(REAL_PATH "${pkgdatadir}" pkgdatadir)
file(REAL_PATH "${prefix}/${CJ_DATADIR}/casteljau" want_datadir)
if(NOT pkgdatadir STREQUAL want_datadir)
  message(FATAL_ERROR "pkgdatadir is '${pkgdatadir}', expected '${want_datadir}'")
endif()
separate_arguments(extra UNIX_COMMAND "${CJ_EXTRA_FLAGS}")
separate_arguments(extra_link UNIX_COMMAND "${CJ_EXTRA_LINK_FLAGS}")
# A non-system prefix: the loader is told where, as a user of such a prefix would.
set(ENV{LD_LIBRARY_PATH} ${libdir})
set(pc_programs "consumer curves ${CJ_CONSUMER_DIR}/main.c"
  "curve_flatten curves ${CJ_EXAMPLES_DIR}/curve_flatten.c")
foreach(c IN LISTS all_parts)
  if(NOT c STREQUAL "curves")
    list(APPEND pc_programs "${c} ${c} ${CJ_CONSUMER_DIR}/component.c")
  endif()
endforeach()
if("viz" IN_LIST all_parts)
  list(APPEND pc_programs "render_scene viz ${CJ_EXAMPLES_DIR}/render_scene.c"
    "animate_frames viz ${CJ_EXAMPLES_DIR}/animate_frames.c")
endif()
foreach(p IN LISTS pc_programs)
  separate_arguments(p UNIX_COMMAND "${p}")
  list(GET p 0 key)
  list(GET p 1 module)
  list(GET p 2 src)
  set(static_arg)
  if(NOT CJ_SHARED)
    set(static_arg --static) # static archives: the private libraries too
  endif()
  run("pkg-config --cflags --libs casteljau-${module}" ${PKG_CONFIG_EXECUTABLE} --cflags --libs
    ${static_arg} casteljau-${module})
  separate_arguments(flags UNIX_COMMAND "${run_out}")
  string(TOUPPER ${key} KEY)
  run("compiling ${key} with pkg-config casteljau-${module}" ${CJ_C_COMPILER} ${extra} -std=c11
    -DCJ_PART_${KEY} ${src} -o ${CJ_WORK_DIR}/pc-${key} ${flags} ${extra_link})
  run_program("pkg-config program ${key}" ${CJ_WORK_DIR}/pc-${key} ${key})
endforeach()
# The umbrella casteljau.pc: everything but the VTK adapter.
if("viz" IN_LIST all_parts)
  run("pkg-config --cflags --libs casteljau" ${PKG_CONFIG_EXECUTABLE} --cflags --libs ${static_arg}
    casteljau)
  separate_arguments(flags UNIX_COMMAND "${run_out}")
  run("compiling render_scene with pkg-config casteljau" ${CJ_C_COMPILER} ${extra} -std=c11
    ${CJ_EXAMPLES_DIR}/render_scene.c -o ${CJ_WORK_DIR}/pc-umbrella ${flags} ${extra_link})
  run_program("pkg-config program (casteljau.pc)" ${CJ_WORK_DIR}/pc-umbrella render_scene)
  list(APPEND pc_programs umbrella)
  find_program(LDD ldd)
  if(CJ_SHARED AND LDD)
    run("ldd pc-umbrella" ${LDD} ${CJ_WORK_DIR}/pc-umbrella)
    if(run_out MATCHES "libvtk|libcasteljau_vtk")
      message(FATAL_ERROR "a program linked with `pkg-config --libs casteljau` loads VTK:\n${run_out}")
    endif()
  endif()
endif()
list(LENGTH pc_programs npc)
message(STATUS "pkg-config: ${npc} programs compiled with plain `pkg-config --cflags --libs casteljau-<component>` and run")

# ---- 4. ldd ----
unset(ENV{LD_LIBRARY_PATH})
if(CJ_SHARED)
  find_program(LDD ldd)
  if(LDD)
    file(REAL_PATH "${libdir}" real_libdir)
    run("ldd casteljau" ${LDD} ${prefix}/bin/casteljau)
    set(tool_ldd "${run_out}")
    if(tool_ldd MATCHES "not found")
      message(FATAL_ERROR "the installed casteljau lacks a library:\n${tool_ldd}")
    endif()
    foreach(m IN LISTS CJ_MODULES)
      if(tool_ldd MATCHES "libcasteljau_${m}\\.so[^ ]* => ([^ ]+)")
        file(REAL_PATH "${CMAKE_MATCH_1}" got)
        get_filename_component(got_dir "${got}" DIRECTORY)
        if(NOT got_dir STREQUAL real_libdir)
          message(FATAL_ERROR "the installed casteljau loads ${got}, not the prefix's")
        endif()
      endif()
    endforeach()
    if(tool_ldd MATCHES "libvtk")
      message(FATAL_ERROR "the installed casteljau loads VTK:\n${tool_ldd}")
    endif()
    string(REGEX MATCHALL "\n" lines "${tool_ldd}")
    list(LENGTH lines ntool)
    # The curves-only programs, built both ways, with the RUNPATH find_package gave or none.
    set(ENV{LD_LIBRARY_PATH} ${libdir})
    foreach(exe ${CJ_WORK_DIR}/cmake-curves/consumer ${CJ_WORK_DIR}/pc-consumer)
      run("ldd ${exe}" ${LDD} ${exe})
      set(curves_ldd "${run_out}")
      foreach(bad "libGL" "libX11" "libglfw" "libvtk" "libexpat" "liblz4" "liblzma"
                  "libcasteljau_(surfaces|scene|raster|viz|vtk)" "not found")
        if(curves_ldd MATCHES "${bad}")
          message(FATAL_ERROR "the curves-only program ${exe} needs ${bad}:\n${curves_ldd}")
        endif()
      endforeach()
      if(NOT curves_ldd MATCHES "libcasteljau_curves\\.so\\.${CJ_SOVERSION} => ${libdir}")
        message(FATAL_ERROR "${exe} does not load the installed libcasteljau_curves:\n${curves_ldd}")
      endif()
      string(REGEX MATCHALL "\n" lines "${curves_ldd}")
      list(LENGTH lines ncurves)
    endforeach()
    unset(ENV{LD_LIBRARY_PATH})
    message(STATUS "ldd: the installed casteljau loads ${ntool} libraries (ours from the prefix, no VTK); a curves-only program ${ncurves}, none of GL/X11/GLFW/VTK/expat/LZ4/LZMA")
  endif()
endif()

# ---- 5. man -l ----
find_program(MAN man)
if(MAN)
  run("man -l casteljau-render.1" ${CMAKE_COMMAND} -E env MANWIDTH=80 MANPAGER=cat PAGER=cat
    ${MAN} -l ${prefix}/${CJ_MANDIR}/man1/casteljau-render.1)
  expect("man -l casteljau-render.1" "${run_out}" "casteljau-render +- +render +a +3D.*SYNOPSIS.*casteljau render.*--width")
  message(STATUS "man -l: casteljau-render(1) renders (NAME, SYNOPSIS, options)")
endif()

# ---- 5b. the installed bash completion, driving the installed tool ----
find_program(BASH bash)
if(BASH AND CJ_COMPLETION_CHECK)
  run("installed bash completion" ${BASH} ${CJ_COMPLETION_CHECK}
    ${prefix}/${CJ_DATADIR}/bash-completion/completions/casteljau ${prefix}/bin/casteljau)
  expect("installed bash completion" "${run_out}" "ok: casteljau ren -> 'render'")
  message(STATUS "bash completion: the installed file completes the installed tool's commands and options")
endif()

# ---- 6. Python from the installed tree ----
if(CJ_PYTHON)
  set(py [=[
import os, casteljau
b = casteljau.Bezier([[0, 0], [1, 2], [2, 0]])
p = b.eval(0.5)
maps = [l.split()[-1] for l in open("/proc/self/maps") if "libcasteljau_curves" in l] + ["(static)"]
print("module", os.path.realpath(casteljau.__file__))
print("library", os.path.realpath(maps[0]))
print("eval", float(p[0]), float(p[1]))
print("teapot patches", len(casteljau.teapot()))
]=])
  run("python3 import casteljau (installed)" ${CMAKE_COMMAND} -E env
    PYTHONPATH=${prefix}/${CJ_PYTHON_DIR} PYTHONDONTWRITEBYTECODE=1 ${CJ_PYTHON} -c "${py}")
  file(REAL_PATH "${prefix}" real_prefix)
  expect("python3 (installed)" "${run_out}" "module ${real_prefix}/${CJ_PYTHON_DIR}/casteljau/")
  if(CJ_SHARED)
    expect("python3 (installed)" "${run_out}" "library ${real_prefix}/${CJ_LIBDIR}/libcasteljau_curves")
  endif()
  expect("python3 (installed)" "${run_out}" "eval 1(\\.0)? 1(\\.0)?\nteapot patches 32")
  message(STATUS "python3: import casteljau from ${CJ_PYTHON_DIR}, the installed library, teapot found")
endif()

# ---- 7. the installed tool renders a shipped scene ----
run("installed render of the shipped teapot scene" ${prefix}/bin/casteljau render
  ${prefix}/${CJ_DATADIR}/casteljau/scenes/teapot.json -o ${CJ_WORK_DIR}/teapot.png --width 96
  --height 72 --quiet)
if(NOT EXISTS ${CJ_WORK_DIR}/teapot.png)
  message(FATAL_ERROR "the installed render wrote no teapot.png")
endif()
message(STATUS "installed casteljau rendered share/casteljau/scenes/teapot.json (its texture found)")
message(STATUS "install test: all checks passed")
