# cj_add_module(NAME SOURCES ... [DEPENDS cj::x ...] [PRIVATE_LIBS ...])
# One library per layer: target casteljau_<NAME>, alias cj::<NAME>, public headers in
# <NAME>/include/casteljau/ installed under include/casteljau/, exported for find_package as
# the component <NAME> (its own export set, casteljau_<NAME>Targets.cmake).
#
# Shared by default (issue 25): libcasteljau_<NAME>.so.<VERSION> with the SONAME
# libcasteljau_<NAME>.so.<SOVERSION>. A program then links only the libraries it calls, and the
# outside libraries a module uses privately (LAPACKE, cJSON, FreeType, VTK, GL...) stay that
# module's business: a consumer of cj::curves resolves none of them. Only symbols named cj_*
# leave a library (cmake/casteljau.map); the rest (file-local helpers of several files,
# inlined C++ templates) are local. CJ_BUILD_SHARED=OFF builds and installs static archives
# instead (the .pc files carry Libs.private/Requires.private for that flavour).
# (The libFuzzer build, CI's second pass, stays static: its coverage instrumentation and
# sanitizer runtimes then live in one executable, and CI builds both flavours.)
if(CJ_FUZZ)
  set(cj_shared_default OFF)
else()
  set(cj_shared_default ON)
endif()
option(CJ_BUILD_SHARED "Build the module libraries as shared libraries (else static)"
  ${cj_shared_default})
# 0.x releases promise nothing across minor versions (casteljauConfigVersion.cmake says
# SameMinorVersion), so the SONAME carries major.minor until 1.0, then the major alone.
if(PROJECT_VERSION_MAJOR EQUAL 0)
  set(CJ_SOVERSION ${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR})
else()
  set(CJ_SOVERSION ${PROJECT_VERSION_MAJOR})
endif()
set(CJ_VERSION_SCRIPT ${CMAKE_CURRENT_LIST_DIR}/casteljau.map)
# Installed programs and libraries find the libraries relative to themselves ($ORIGIN), so a
# moved prefix keeps working; none when the library folder is one the linker searches anyway.
list(FIND CMAKE_C_IMPLICIT_LINK_DIRECTORIES "${CMAKE_INSTALL_FULL_LIBDIR}" cj_libdir_implicit)
if(cj_libdir_implicit EQUAL -1)
  set(CJ_INSTALL_RPATH_NEEDED ON)
else()
  set(CJ_INSTALL_RPATH_NEEDED OFF)
endif()

# cj_install_rpath(TARGET DESTINATION): the target, installed in DESTINATION (relative to the
# prefix), finds the module libraries through an $ORIGIN-relative RUNPATH.
function(cj_install_rpath target destination)
  if(NOT CJ_INSTALL_RPATH_NEEDED OR NOT CJ_BUILD_SHARED)
    return()
  endif()
  file(RELATIVE_PATH rel "${CMAKE_INSTALL_PREFIX}/${destination}"
    "${CMAKE_INSTALL_FULL_LIBDIR}")
  if(rel STREQUAL "")
    set(rel ".")
  endif()
  set_property(TARGET ${target} APPEND PROPERTY INSTALL_RPATH "$ORIGIN/${rel}")
endfunction()

function(cj_add_module name)
  cmake_parse_arguments(M "" "" "SOURCES;DEPENDS;PRIVATE_LIBS" ${ARGN})
  set(tgt casteljau_${name})
  if(CJ_BUILD_SHARED)
    add_library(${tgt} SHARED ${M_SOURCES})
    set_target_properties(${tgt} PROPERTIES VERSION ${PROJECT_VERSION} SOVERSION ${CJ_SOVERSION}
      LINK_DEPENDS ${CJ_VERSION_SCRIPT})
    # Calls between functions of one library bind inside it (as they did in the archives),
    # not through the PLT; a missing dependency is a link error here, not at a user's.
    target_link_options(${tgt} PRIVATE LINKER:--version-script=${CJ_VERSION_SCRIPT}
      LINKER:-Bsymbolic-functions)
    if(NOT CJ_SANITIZE)
      target_link_options(${tgt} PRIVATE LINKER:--no-undefined)
    endif()
    cj_install_rpath(${tgt} ${CMAKE_INSTALL_LIBDIR})
  else()
    add_library(${tgt} STATIC ${M_SOURCES})
  endif()
  add_library(cj::${name} ALIAS ${tgt})
  set_target_properties(${tgt} PROPERTIES EXPORT_NAME ${name} POSITION_INDEPENDENT_CODE ON)
  target_include_directories(${tgt}
    PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
           $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>
    PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src)
  target_link_libraries(${tgt} PUBLIC ${M_DEPENDS} PRIVATE ${M_PRIVATE_LIBS})
  cj_warnings(${tgt})
  install(TARGETS ${tgt} EXPORT casteljau_${name}Targets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR} NAMELINK_COMPONENT Development)
  if(EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/include/casteljau)
    install(DIRECTORY include/casteljau DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  endif()
  set_property(GLOBAL APPEND PROPERTY CJ_MODULES ${name})
  # At the end of this directory (after any later target_link_libraries on ${tgt}, and while
  # the directory-scoped imported targets of find_package/pkg_check_modules are visible),
  # record what consumers of the installed package must resolve: see cj_record_install_deps.
  # (DEFER expands arguments when the call runs, so bake the name in with EVAL now.)
  cmake_language(EVAL CODE "cmake_language(DEFER CALL cj_record_install_deps [[${name}]])")
endfunction()

# cj_record_install_deps(NAME): scans the link libraries of casteljau_<NAME> and records, in
# global properties per module read by cmake/CjInstall.cmake:
#   CJ_MODULE_DEPS_<NAME>          the other modules it links (public or private)
#   CJ_CONFIG_DEPS_<NAME>          lines for its component in casteljauConfig.cmake
#                                  (find_dependency(...) for packages with a CMake config or
#                                  find module; pkg-config imported targets re-created as
#                                  INTERFACE IMPORTED targets with the libraries found at build
#                                  time). For a shared library only its INTERFACE links count:
#                                  what it links privately is resolved by the loader.
#   CJ_VTK_COMPONENTS_<NAME>       VTK components for find_dependency(VTK COMPONENTS ...)
#   CJ_PC_REQUIRES_PRIVATE_<NAME> / CJ_PC_LIBS_PRIVATE_<NAME>   the same for its .pc file
#                                  (all links: what `pkg-config --static` needs)
function(cj_record_install_deps name)
  set(tgt casteljau_${name})
  get_target_property(type ${tgt} TYPE)
  get_target_property(l1 ${tgt} LINK_LIBRARIES)
  get_target_property(l2 ${tgt} INTERFACE_LINK_LIBRARIES)
  get_target_property(srcs ${tgt} SOURCES)
  set(pc_libs)
  foreach(s IN LISTS srcs)
    if(s MATCHES "\\.(cpp|cxx|cc)$")
      set(pc_libs -lstdc++)
    endif()
  endforeach()
  set(seen)
  set(modules)
  set(config)
  set(vtk)
  set(pc_req)
  foreach(item IN LISTS l1 l2)
    if(item MATCHES "^\\$<LINK_ONLY:(.*)>$")
      set(item "${CMAKE_MATCH_1}")
    endif()
    if(item MATCHES "^(cj::|casteljau_)(.+)$")
      list(APPEND modules ${CMAKE_MATCH_2})
      continue()
    endif()
    if(item MATCHES "/libm\\.(so|a)$")
      set(item m) # the C library's libm, by name in .pc files
    endif()
    if(NOT item OR item MATCHES "NOTFOUND$" OR item MATCHES "^\\$<" OR item IN_LIST seen)
      continue()
    endif()
    list(APPEND seen "${item}")
    # A shared library's private links are not the consumer's to find.
    set(for_config ON)
    if(type STREQUAL "SHARED_LIBRARY" AND NOT item IN_LIST l2)
      set(for_config OFF)
    endif()
    set(cfg)
    if(item MATCHES "^VTK::(.+)$")
      if(for_config)
        list(APPEND vtk ${CMAKE_MATCH_1})
      endif()
      get_target_property(loc ${item} LOCATION)
      if(loc)
        list(APPEND pc_libs "${loc}")
      endif()
    elseif(item STREQUAL "Freetype::Freetype")
      set(cfg "find_dependency(Freetype)")
      list(APPEND pc_req freetype2)
    elseif(item STREQUAL "glfw")
      set(cfg "find_dependency(glfw3)")
      list(APPEND pc_req glfw3)
    elseif(item MATCHES "^Threads::")
      set(cfg "find_dependency(Threads)")
      list(APPEND pc_libs -pthread)
    elseif(item MATCHES "^PkgConfig::(.+)$" AND TARGET ${item})
      set(props)
      foreach(p INTERFACE_LINK_LIBRARIES INTERFACE_LINK_DIRECTORIES INTERFACE_LINK_OPTIONS)
        get_target_property(v ${item} ${p})
        if(v)
          # (a placeholder keeps the list in one property entry; CjInstall.cmake restores it)
          string(REPLACE ";" "__CJ_SEMICOLON__" v "${v}")
          string(APPEND props " ${p} \"${v}\"")
        endif()
      endforeach()
      set(cfg "if(NOT TARGET ${item})\n  add_library(${item} INTERFACE IMPORTED)\n  set_target_properties(${item} PROPERTIES${props})\nendif()")
      get_target_property(v ${item} INTERFACE_LINK_LIBRARIES)
      if(v)
        list(APPEND pc_libs ${v})
      endif()
    elseif(item MATCHES "^([A-Za-z0-9_]+)::")
      # Best guess for other namespaced imported targets: the package of that name.
      set(cfg "find_dependency(${CMAKE_MATCH_1})")
    elseif(IS_ABSOLUTE "${item}" OR item MATCHES "^-")
      list(APPEND pc_libs "${item}")
    else()
      list(APPEND pc_libs "-l${item}")
    endif()
    if(cfg AND for_config)
      set_property(GLOBAL APPEND PROPERTY CJ_CONFIG_DEPS_${name} "${cfg}")
    endif()
  endforeach()
  list(REMOVE_DUPLICATES modules)
  list(REMOVE_ITEM modules ${name})
  set_property(GLOBAL PROPERTY CJ_MODULE_DEPS_${name} ${modules})
  set_property(GLOBAL PROPERTY CJ_VTK_COMPONENTS_${name} ${vtk})
  set_property(GLOBAL PROPERTY CJ_PC_REQUIRES_PRIVATE_${name} ${pc_req})
  set_property(GLOBAL PROPERTY CJ_PC_LIBS_PRIVATE_${name} ${pc_libs})
endfunction()
