# cj_add_module(NAME SOURCES ... [DEPENDS cj::x ...] [PRIVATE_LIBS ...])
# One library per layer: target casteljau_<NAME>, alias cj::<NAME>, public headers in
# <NAME>/include/casteljau/ installed under include/casteljau/, exported for find_package.
function(cj_add_module name)
  cmake_parse_arguments(M "" "" "SOURCES;DEPENDS;PRIVATE_LIBS" ${ARGN})
  set(tgt casteljau_${name})
  add_library(${tgt} ${M_SOURCES})
  add_library(cj::${name} ALIAS ${tgt})
  set_target_properties(${tgt} PROPERTIES EXPORT_NAME ${name} POSITION_INDEPENDENT_CODE ON)
  target_include_directories(${tgt}
    PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
           $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>
    PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src)
  target_link_libraries(${tgt} PUBLIC ${M_DEPENDS} PRIVATE ${M_PRIVATE_LIBS})
  cj_warnings(${tgt})
  install(TARGETS ${tgt} EXPORT casteljauTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(DIRECTORY include/casteljau DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  # pkg-config lists the libraries in link order (higher layers first).
  get_property(libs GLOBAL PROPERTY CJ_PC_LIBS)
  set_property(GLOBAL PROPERTY CJ_PC_LIBS -l${tgt} ${libs})
endfunction()
