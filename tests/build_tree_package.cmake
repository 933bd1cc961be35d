# CTest script (cmake -P): a separate project finds casteljau in the BUILD tree (no install)
# through find_package(casteljau) with casteljau_DIR = the build folder, links cj::curves,
# builds and runs. Inputs (-D): CJ_BUILD_DIR CJ_WORK_DIR CJ_CONSUMER_DIR CJ_C_COMPILER
# CJ_CXX_COMPILER CJ_GENERATOR CJ_EXTRA_FLAGS.
cmake_minimum_required(VERSION 3.20)
set(expected "casteljau consumer: c\\(0\\.5\\) = 1 1")
file(REMOVE_RECURSE ${CJ_WORK_DIR})
set(flag_args)
if(CJ_EXTRA_FLAGS)
  set(flag_args "-DCMAKE_C_FLAGS=${CJ_EXTRA_FLAGS}" "-DCMAKE_CXX_FLAGS=${CJ_EXTRA_FLAGS}"
                "-DCMAKE_EXE_LINKER_FLAGS=${CJ_EXTRA_FLAGS}")
endif()
foreach(step configure build run)
  if(step STREQUAL configure)
    set(cmd ${CMAKE_COMMAND} -S ${CJ_CONSUMER_DIR} -B ${CJ_WORK_DIR} -G ${CJ_GENERATOR}
        -DCMAKE_BUILD_TYPE=Release -Dcasteljau_DIR=${CJ_BUILD_DIR}
        -DCMAKE_C_COMPILER=${CJ_C_COMPILER} -DCMAKE_CXX_COMPILER=${CJ_CXX_COMPILER} ${flag_args})
  elseif(step STREQUAL build)
    set(cmd ${CMAKE_COMMAND} --build ${CJ_WORK_DIR})
  else()
    set(cmd ${CJ_WORK_DIR}/consumer)
  endif()
  execute_process(COMMAND ${cmd} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "build-tree package: ${step} failed (${rc}):\n${out}\n${err}")
  endif()
endforeach()
if(NOT out MATCHES "${expected}")
  message(FATAL_ERROR "build-tree consumer printed:\n${out}")
endif()
message(STATUS "find_package(casteljau) from the build tree ${CJ_BUILD_DIR}: ${out}")
