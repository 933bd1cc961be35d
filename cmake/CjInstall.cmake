# Install rules: headers (per module, by cj_add_module), the exported targets cj::<module>,
# casteljauConfig.cmake (+ version file) for find_package, and a relocatable casteljau.pc.
# Included once from the top-level CMakeLists.txt after every module directory is processed,
# so it sees every module other helpers add (cj_add_module records them in CJ_MODULES and
# their outside link dependencies through cj_record_install_deps).
include(CMakePackageConfigHelpers)
set(CJ_CMAKE_INSTALL_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/casteljau)

get_property(CJ_MODULES GLOBAL PROPERTY CJ_MODULES)
get_property(cj_deps GLOBAL PROPERTY CJ_CONFIG_DEPS)
get_property(cj_vtk GLOBAL PROPERTY CJ_VTK_COMPONENTS)
if(cj_vtk)
  list(REMOVE_DUPLICATES cj_vtk)
  string(JOIN " " cj_vtk_str ${cj_vtk})
  list(PREPEND cj_deps "find_dependency(VTK COMPONENTS ${cj_vtk_str})")
endif()
if(cj_deps)
  list(REMOVE_DUPLICATES cj_deps)
  string(JOIN "\n" CJ_CONFIG_DEPENDENCIES ${cj_deps})
  string(REPLACE "__CJ_SEMICOLON__" ";" CJ_CONFIG_DEPENDENCIES "${CJ_CONFIG_DEPENDENCIES}")
else()
  set(CJ_CONFIG_DEPENDENCIES "# (none)")
endif()
string(JOIN " " CJ_CONFIG_MODULES ${CJ_MODULES})

install(EXPORT casteljauTargets NAMESPACE cj:: DESTINATION ${CJ_CMAKE_INSTALL_DIR})
# The build tree is a package too: find_package(casteljau) with casteljau_DIR (or
# CMAKE_PREFIX_PATH) set to the build folder uses the libraries in place, without installing.
# The casteljauConfig.cmake generated below sits beside this file and includes it.
export(EXPORT casteljauTargets NAMESPACE cj:: FILE ${PROJECT_BINARY_DIR}/casteljauTargets.cmake)
configure_package_config_file(cmake/casteljauConfig.cmake.in
  ${PROJECT_BINARY_DIR}/casteljauConfig.cmake
  INSTALL_DESTINATION ${CJ_CMAKE_INSTALL_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/casteljauConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/casteljauConfig.cmake
  ${PROJECT_BINARY_DIR}/casteljauConfigVersion.cmake
  DESTINATION ${CJ_CMAKE_INSTALL_DIR})

# pkg-config. The prefix is found relative to the .pc file (${pcfiledir}), so the package
# works wherever it is installed (cmake --install --prefix ...), not only at
# CMAKE_INSTALL_PREFIX. Libs lists the archives higher layers first; Libs.private and
# Requires.private carry the outside libraries for `pkg-config --static`.
get_property(CJ_PC_LIBS GLOBAL PROPERTY CJ_PC_LIBS)
string(JOIN " " CJ_PC_LIBS_STR ${CJ_PC_LIBS})
if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
  set(CJ_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
  set(CJ_PC_LIBDIR "${CMAKE_INSTALL_LIBDIR}")
else()
  file(RELATIVE_PATH cj_up "/root/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/root")
  string(REGEX REPLACE "/$" "" cj_up "${cj_up}")
  set(CJ_PC_PREFIX "\${pcfiledir}/${cj_up}")
  set(CJ_PC_LIBDIR "\${prefix}/${CMAKE_INSTALL_LIBDIR}")
endif()
if(IS_ABSOLUTE "${CMAKE_INSTALL_INCLUDEDIR}")
  set(CJ_PC_INCLUDEDIR "${CMAKE_INSTALL_INCLUDEDIR}")
else()
  set(CJ_PC_INCLUDEDIR "\${prefix}/${CMAKE_INSTALL_INCLUDEDIR}")
endif()
get_property(cj_pc_priv GLOBAL PROPERTY CJ_PC_LIBS_PRIVATE)
get_property(cj_has_cxx GLOBAL PROPERTY CJ_HAS_CXX)
if(cj_has_cxx)
  list(APPEND cj_pc_priv -lstdc++)
endif()
if(cj_pc_priv)
  list(REMOVE_DUPLICATES cj_pc_priv)
endif()
string(JOIN " " CJ_PC_LIBS_PRIVATE ${cj_pc_priv})
get_property(cj_pc_req GLOBAL PROPERTY CJ_PC_REQUIRES_PRIVATE)
if(cj_pc_req)
  list(REMOVE_DUPLICATES cj_pc_req)
endif()
string(JOIN " " CJ_PC_REQUIRES_PRIVATE ${cj_pc_req})
configure_file(cmake/casteljau.pc.in ${PROJECT_BINARY_DIR}/casteljau.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/casteljau.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
