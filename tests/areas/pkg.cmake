# Packages that behave like packages (issue 25; docs/packaging.md).
get_property(cj_pkg_modules GLOBAL PROPERTY CJ_MODULES)

# Each module's shared library exports only cj_* symbols and has its versioned SONAME.
if(CJ_BUILD_SHARED)
  set(cj_pkg_libs)
  foreach(m IN LISTS cj_pkg_modules)
    list(APPEND cj_pkg_libs $<TARGET_FILE:casteljau_${m}>)
  endforeach()
  add_test(NAME test_exported_symbols COMMAND ${CMAKE_COMMAND} -DCJ_NM=${CMAKE_NM}
    -DCJ_READELF=${CMAKE_READELF} "-DCJ_LIBS=${cj_pkg_libs}" -DCJ_SOVERSION=${CJ_SOVERSION}
    -P ${CMAKE_CURRENT_SOURCE_DIR}/pkg/exported_symbols.cmake)
endif()

# cmake --install into a temporary prefix; examples/ and one program per component built there
# with find_package and with pkg-config, and run; ldd, man -l, Python from the installed tree
# (tests/install/run_install_test.cmake).
set(cj_install_flags "")
set(cj_install_link_flags "")
if(CJ_SANITIZE)
  set(cj_install_flags "-fsanitize=address,undefined")
  if(CMAKE_C_COMPILER_ID MATCHES "Clang")
    # The image plug-in is C++: a C program that loads it needs UBSan's C++ runtime (vptr
    # checks), which clang links into C programs only when asked (app/ links as C++ instead).
    set(cj_install_link_flags "-fsanitize-link-c++-runtime -lstdc++")
  endif()
endif()
set(cj_install_python "")
if(TARGET casteljau_python)
  get_property(cj_install_python GLOBAL PROPERTY CJ_PYTHON_EXECUTABLE)
endif()
add_test(NAME test_install COMMAND ${CMAKE_COMMAND}
  -DCJ_BUILD_DIR=${PROJECT_BINARY_DIR} -DCJ_WORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/install_test
  -DCJ_CONSUMER_DIR=${CMAKE_CURRENT_SOURCE_DIR}/install/consumer
  -DCJ_EXAMPLES_DIR=${PROJECT_SOURCE_DIR}/examples
  -DCJ_LIBDIR=${CMAKE_INSTALL_LIBDIR} -DCJ_DATADIR=${CMAKE_INSTALL_DATADIR}
  -DCJ_MANDIR=${CMAKE_INSTALL_MANDIR} -DCJ_C_COMPILER=${CMAKE_C_COMPILER}
  -DCJ_GENERATOR=${CMAKE_GENERATOR} -DCJ_CONFIG=$<CONFIG> -DCJ_EXTRA_FLAGS=${cj_install_flags}
  -DCJ_EXTRA_LINK_FLAGS=${cj_install_link_flags}
  -DCJ_SOVERSION=${CJ_SOVERSION} "-DCJ_MODULES=${cj_pkg_modules}" -DCJ_SHARED=${CJ_BUILD_SHARED}
  -DCJ_PYTHON=${cj_install_python} -DCJ_PYTHON_DIR=${CJ_PYTHON_INSTALL_DIR}
  -DCJ_COMPLETION_CHECK=${CMAKE_CURRENT_SOURCE_DIR}/completion_check.sh
  -P ${CMAKE_CURRENT_SOURCE_DIR}/install/run_install_test.cmake)
set_tests_properties(test_install PROPERTIES TIMEOUT 600 RESOURCE_LOCK cj_install)
