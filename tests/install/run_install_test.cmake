# CTest script (cmake -P): installs the build tree into a temporary prefix, then builds and
# runs a separate consumer project against that installation twice: through
# find_package(casteljau) + cj::curves, and through pkg-config (casteljau.pc) with a plain
# compiler call. The prefix differs from CMAKE_INSTALL_PREFIX, so this also checks that the
# installed CMake package and the .pc file are relocatable.
#
# Inputs (-D): CJ_BUILD_DIR CJ_WORK_DIR CJ_CONSUMER_DIR CJ_LIBDIR CJ_C_COMPILER
#              CJ_CXX_COMPILER CJ_GENERATOR CJ_CONFIG CJ_EXTRA_FLAGS (e.g. sanitizer flags)
cmake_minimum_required(VERSION 3.20)
foreach(v CJ_BUILD_DIR CJ_WORK_DIR CJ_CONSUMER_DIR CJ_LIBDIR CJ_C_COMPILER CJ_GENERATOR)
  if(NOT DEFINED ${v} OR "${${v}}" STREQUAL "")
    message(FATAL_ERROR "run_install_test.cmake: ${v} is not set")
  endif()
endforeach()
set(expected "casteljau consumer: c\\(0\\.5\\) = 1 1, bbox 0 0 2 1, moved 11 21, status: parameter out of range")
set(prefix ${CJ_WORK_DIR}/prefix)
file(REMOVE_RECURSE ${CJ_WORK_DIR})
file(MAKE_DIRECTORY ${CJ_WORK_DIR})

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${ARGN}\n${out}\n${err}")
  endif()
  set(run_out "${out}" PARENT_SCOPE)
endfunction()

# 1. Install.
set(cfg_args)
if(CJ_CONFIG)
  set(cfg_args --config ${CJ_CONFIG})
endif()
run("cmake --install" ${CMAKE_COMMAND} --install ${CJ_BUILD_DIR} --prefix ${prefix} ${cfg_args})
foreach(f include/casteljau/bezier.h include/casteljau/transform.h
          ${CJ_LIBDIR}/libcasteljau_curves.a ${CJ_LIBDIR}/cmake/casteljau/casteljauConfig.cmake
          ${CJ_LIBDIR}/cmake/casteljau/casteljauConfigVersion.cmake
          ${CJ_LIBDIR}/pkgconfig/casteljau.pc)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "installed tree lacks ${f}")
  endif()
endforeach()
file(GLOB headers RELATIVE ${prefix}/include/casteljau ${prefix}/include/casteljau/*.h)
list(LENGTH headers nheaders)
message(STATUS "installed ${nheaders} public headers into ${prefix}")

# 2. find_package(casteljau) consumer.
set(flag_args)
if(CJ_EXTRA_FLAGS)
  set(flag_args "-DCMAKE_C_FLAGS=${CJ_EXTRA_FLAGS}" "-DCMAKE_CXX_FLAGS=${CJ_EXTRA_FLAGS}"
                "-DCMAKE_EXE_LINKER_FLAGS=${CJ_EXTRA_FLAGS}")
endif()
run("configuring the find_package consumer" ${CMAKE_COMMAND} -S ${CJ_CONSUMER_DIR}
    -B ${CJ_WORK_DIR}/cmake-consumer -G ${CJ_GENERATOR} -DCMAKE_BUILD_TYPE=Release
    -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_C_COMPILER=${CJ_C_COMPILER}
    -DCMAKE_CXX_COMPILER=${CJ_CXX_COMPILER} ${flag_args})
run("building the find_package consumer" ${CMAKE_COMMAND} --build ${CJ_WORK_DIR}/cmake-consumer)
run("running the find_package consumer" ${CJ_WORK_DIR}/cmake-consumer/consumer)
if(NOT run_out MATCHES "${expected}")
  message(FATAL_ERROR "find_package consumer printed:\n${run_out}\nexpected:\n${expected}")
endif()
message(STATUS "find_package(casteljau) + cj::curves: ${run_out}")

# 3. pkg-config consumer: a plain compiler call with the flags casteljau.pc gives.
find_program(PKG_CONFIG_EXECUTABLE NAMES pkg-config pkgconf REQUIRED)
set(ENV{PKG_CONFIG_PATH} ${prefix}/${CJ_LIBDIR}/pkgconfig)
run("pkg-config --cflags" ${PKG_CONFIG_EXECUTABLE} --cflags casteljau)
string(STRIP "${run_out}" cflags)
run("pkg-config --libs" ${PKG_CONFIG_EXECUTABLE} --libs casteljau)
string(STRIP "${run_out}" libs)
run("pkg-config --static --libs" ${PKG_CONFIG_EXECUTABLE} --static --libs casteljau)
separate_arguments(cflags UNIX_COMMAND "${cflags}")
separate_arguments(libs UNIX_COMMAND "${libs}")
separate_arguments(extra UNIX_COMMAND "${CJ_EXTRA_FLAGS}")
run("compiling the pkg-config consumer" ${CJ_C_COMPILER} ${extra} -std=c11
    ${CJ_CONSUMER_DIR}/main.c ${cflags} -o ${CJ_WORK_DIR}/pc-consumer ${libs})
run("running the pkg-config consumer" ${CJ_WORK_DIR}/pc-consumer)
if(NOT run_out MATCHES "${expected}")
  message(FATAL_ERROR "pkg-config consumer printed:\n${run_out}\nexpected:\n${expected}")
endif()
message(STATUS "pkg-config casteljau: ${run_out}")
message(STATUS "install test: cmake --install, find_package and pkg-config consumers all ok")
