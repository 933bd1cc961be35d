# Install rules: headers (per module, by cj_add_module), one exported target set per module
# (component), casteljauConfig.cmake (+ version file) for find_package, one relocatable .pc file
# per module (casteljau-<module>.pc) plus casteljau.pc for all of them, the shared data and
# its folder's name for both. Included once from the top-level CMakeLists.txt after every
# module directory is processed, so it sees every module other helpers add (cj_add_module
# records them in CJ_MODULES and their dependencies through cj_record_install_deps).
include(CMakePackageConfigHelpers)
set(CJ_CMAKE_INSTALL_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/casteljau)
# The shipped data (scenes, textures, the teapot) and the documentation.
set(CJ_DATA_INSTALL_DIR ${CMAKE_INSTALL_DATADIR}/casteljau)

get_property(CJ_MODULES GLOBAL PROPERTY CJ_MODULES)

# ---- CMake package: one file per component, read only when that component is asked for ----
# casteljau_<m>Deps.cmake finds what the component's targets name (for shared libraries: only
# their public links; nothing outside the project today), then casteljau_<m>Targets.cmake.
set(CJ_CONFIG_COMPONENT_DEPS "")
foreach(m IN LISTS CJ_MODULES)
  get_property(deps GLOBAL PROPERTY CJ_CONFIG_DEPS_${m})
  get_property(vtk GLOBAL PROPERTY CJ_VTK_COMPONENTS_${m})
  if(vtk)
    list(REMOVE_DUPLICATES vtk)
    string(JOIN " " vtk_str ${vtk})
    list(PREPEND deps "find_dependency(VTK COMPONENTS ${vtk_str})")
  endif()
  if(deps)
    list(REMOVE_DUPLICATES deps)
    string(JOIN "\n" text ${deps})
    string(REPLACE "__CJ_SEMICOLON__" ";" text "${text}")
  else()
    set(text "# (nothing outside casteljau)")
  endif()
  file(GENERATE OUTPUT ${PROJECT_BINARY_DIR}/casteljau_${m}Deps.cmake CONTENT
    "# Written by cmake/CjInstall.cmake: what the component ${m} needs found first.\n${text}\n")
  install(FILES ${PROJECT_BINARY_DIR}/casteljau_${m}Deps.cmake DESTINATION ${CJ_CMAKE_INSTALL_DIR})
  install(EXPORT casteljau_${m}Targets NAMESPACE cj:: DESTINATION ${CJ_CMAKE_INSTALL_DIR})
  # The build tree is a package too: find_package(casteljau) with casteljau_DIR (or
  # CMAKE_PREFIX_PATH) set to the build folder uses the libraries in place, without
  # installing. The casteljauConfig.cmake generated below sits beside these files.
  export(EXPORT casteljau_${m}Targets NAMESPACE cj::
    FILE ${PROJECT_BINARY_DIR}/casteljau_${m}Targets.cmake)
  get_property(mdeps GLOBAL PROPERTY CJ_MODULE_DEPS_${m})
  string(JOIN " " mdeps_str ${mdeps})
  string(APPEND CJ_CONFIG_COMPONENT_DEPS "set(_cj_needs_${m} ${mdeps_str})\n")
endforeach()
string(JOIN " " CJ_CONFIG_MODULES ${CJ_MODULES})
set(CJ_DATA_DIR_FOR_CONFIG ${CJ_DATA_INSTALL_DIR})
configure_package_config_file(cmake/casteljauConfig.cmake.in
  ${PROJECT_BINARY_DIR}/casteljauConfig.cmake
  INSTALL_DESTINATION ${CJ_CMAKE_INSTALL_DIR}
  PATH_VARS CJ_DATA_DIR_FOR_CONFIG)
# In the build tree the config reads casteljauBuildTree.cmake (not installed): its data folder is
# <build>/share/casteljau, laid out as installed with links into the sources.
set(cj_build_data ${PROJECT_BINARY_DIR}/share/casteljau)
file(MAKE_DIRECTORY ${cj_build_data})
file(CREATE_LINK ${PROJECT_SOURCE_DIR}/scenes ${cj_build_data}/scenes SYMBOLIC)
file(CREATE_LINK ${PROJECT_SOURCE_DIR}/data/teapot.bpt ${cj_build_data}/teapot.bpt SYMBOLIC)
file(CREATE_LINK ${PROJECT_SOURCE_DIR}/data/fit_points.txt ${cj_build_data}/fit_points.txt SYMBOLIC)
file(WRITE ${PROJECT_BINARY_DIR}/casteljauBuildTree.cmake
  "# Written by cmake/CjInstall.cmake: the build tree used as a package.\n"
  "set(casteljau_DATA_DIR \"${cj_build_data}\")\n")
write_basic_package_version_file(${PROJECT_BINARY_DIR}/casteljauConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/casteljauConfig.cmake
  ${PROJECT_BINARY_DIR}/casteljauConfigVersion.cmake
  DESTINATION ${CJ_CMAKE_INSTALL_DIR})

# ---- pkg-config ----
# The prefix is found relative to the .pc file (${pcfiledir}), so the package works wherever it
# is installed (cmake --install --prefix ...), not only at CMAKE_INSTALL_PREFIX.
# casteljau-<m>.pc: Libs names the module's own library; Requires the modules its public
# headers build on (so `pkg-config --libs casteljau-raster` links everything a program using
# raster's headers calls); Requires.private / Libs.private the outside libraries and the
# modules it uses privately, which only a static link (`pkg-config --static`) needs.
# casteljau.pc requires every module but vtk.
function(cj_pc_dir var dir)
  if(IS_ABSOLUTE "${dir}")
    set(${var} "${dir}" PARENT_SCOPE)
  else()
    set(${var} "\${prefix}/${dir}" PARENT_SCOPE)
  endif()
endfunction()
if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
  set(CJ_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
else()
  file(RELATIVE_PATH cj_up "/root/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/root")
  string(REGEX REPLACE "/$" "" cj_up "${cj_up}")
  set(CJ_PC_PREFIX "\${pcfiledir}/${cj_up}")
endif()
cj_pc_dir(CJ_PC_LIBDIR "${CMAKE_INSTALL_LIBDIR}")
cj_pc_dir(CJ_PC_INCLUDEDIR "${CMAKE_INSTALL_INCLUDEDIR}")
cj_pc_dir(CJ_PC_DATADIR "${CJ_DATA_INSTALL_DIR}")
set(cj_pc_all)
foreach(m IN LISTS CJ_MODULES)
  set(CJ_PC_NAME casteljau-${m})
  set(CJ_PC_DESCRIPTION "casteljau ${m} library")
  set(CJ_PC_LIBS "-L\${libdir} -lcasteljau_${m}")
  get_target_property(public casteljau_${m} INTERFACE_LINK_LIBRARIES)
  get_property(mdeps GLOBAL PROPERTY CJ_MODULE_DEPS_${m})
  set(req)
  set(req_priv)
  foreach(d IN LISTS mdeps)
    if("cj::${d}" IN_LIST public)
      list(APPEND req casteljau-${d})
    else()
      list(APPEND req_priv casteljau-${d})
    endif()
  endforeach()
  get_property(ext_req GLOBAL PROPERTY CJ_PC_REQUIRES_PRIVATE_${m})
  list(APPEND req_priv ${ext_req})
  get_property(libs_priv GLOBAL PROPERTY CJ_PC_LIBS_PRIVATE_${m})
  list(APPEND libs_priv -lm)
  list(REMOVE_DUPLICATES libs_priv)
  string(JOIN " " CJ_PC_REQUIRES ${req})
  string(JOIN " " CJ_PC_REQUIRES_PRIVATE ${req_priv})
  string(JOIN " " CJ_PC_LIBS_PRIVATE ${libs_priv})
  configure_file(cmake/casteljau.pc.in ${PROJECT_BINARY_DIR}/pkgconfig/casteljau-${m}.pc @ONLY)
  # The umbrella leaves out the VTK adapter: `pkg-config --libs casteljau` must not make every
  # program load VTK; its users ask for casteljau-vtk.
  if(NOT m STREQUAL "vtk")
    list(APPEND cj_pc_all casteljau-${m})
  endif()
endforeach()
set(CJ_PC_NAME casteljau)
set(CJ_PC_DESCRIPTION
  "Curves and surfaces: Bezier evaluation, interpolation, tessellation and rasterization")
set(CJ_PC_LIBS "")
string(JOIN " " CJ_PC_REQUIRES ${cj_pc_all})
set(CJ_PC_REQUIRES_PRIVATE "")
set(CJ_PC_LIBS_PRIVATE "")
configure_file(cmake/casteljau.pc.in ${PROJECT_BINARY_DIR}/pkgconfig/casteljau.pc @ONLY)
install(DIRECTORY ${PROJECT_BINARY_DIR}/pkgconfig/ DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig
  FILES_MATCHING PATTERN "*.pc")

# ---- shared data: share/casteljau (scenes with their meshes and textures, the teapot) ----
install(DIRECTORY ${PROJECT_SOURCE_DIR}/scenes DESTINATION ${CJ_DATA_INSTALL_DIR})
install(FILES ${PROJECT_SOURCE_DIR}/data/fit_points.txt DESTINATION ${CJ_DATA_INSTALL_DIR})
# The documentation (the README and docs/ with its pictures) where Debian puts it.
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR})
