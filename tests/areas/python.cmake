# Python bindings (issue 25): pytest over python/tests, importing the module from the build.
if(TARGET casteljau_python)
  get_property(cj_python GLOBAL PROPERTY CJ_PYTHON_EXECUTABLE)
  add_test(NAME test_python
    COMMAND ${cj_python} -m pytest -v -s -p no:cacheprovider ${PROJECT_SOURCE_DIR}/python/tests)
  set_tests_properties(test_python PROPERTIES
    ENVIRONMENT "PYTHONDONTWRITEBYTECODE=1;PYTHONPATH=${PROJECT_BINARY_DIR}/python;CJ_SOURCE_DIR=${PROJECT_SOURCE_DIR}"
    TIMEOUT 300)
endif()
