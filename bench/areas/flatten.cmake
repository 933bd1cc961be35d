# The fixed workload of the flattening instruction counts (bench/flatten_callgrind.sh) and the
# same-process time ratios against kurbo (issue 20).
add_executable(bench_flatten_icount ${CMAKE_CURRENT_SOURCE_DIR}/bench_flatten_icount.c)
target_link_libraries(bench_flatten_icount PRIVATE cj::curves m)
cj_warnings(bench_flatten_icount)

# Peers measured in the same run as ours (issue 13): cairo's flattening (cairo_copy_path_flat)
# next to bench_flatten's, cairo's anti-aliased strokes next to bench_lines'. cairo is linked
# into these bench programs only, never into the library.
find_package(PkgConfig REQUIRED)
pkg_check_modules(CJ_BENCH_CAIRO IMPORTED_TARGET cairo)
if(CJ_BENCH_CAIRO_FOUND)
  target_link_libraries(bench_flatten PRIVATE PkgConfig::CJ_BENCH_CAIRO)
  target_compile_definitions(bench_flatten PRIVATE CJ_HAVE_CAIRO=1)
  if(TARGET bench_lines)
    target_link_libraries(bench_lines PRIVATE PkgConfig::CJ_BENCH_CAIRO)
    target_compile_definitions(bench_lines PRIVATE CJ_HAVE_CAIRO=1)
  endif()
else()
  message(STATUS "cairo not found: bench_flatten and bench_lines run without the cairo columns")
endif()

# kurbo 0.7 (Levien's flattening) as a peer of bench_flatten (issue 20): bench/kurbo is a small
# Rust static library built offline by cargo against Debian's librust-kurbo-dev (installed by
# scripts/setup.sh); without cargo or the crate the bench runs without the kurbo rows.
set(CJ_CARGO_REGISTRY /usr/share/cargo/registry)
find_program(CJ_CARGO cargo PATHS /usr/bin NO_DEFAULT_PATH)
find_program(CJ_CARGO cargo)
# rustc from cargo's own folder: a rustup cargo driving Debian's older rustc fails.
if(CJ_CARGO)
  get_filename_component(CJ_CARGO_DIR ${CJ_CARGO} DIRECTORY)
  find_program(CJ_RUSTC rustc PATHS ${CJ_CARGO_DIR} NO_DEFAULT_PATH)
endif()
if(CJ_CARGO AND CJ_RUSTC AND EXISTS ${CJ_CARGO_REGISTRY}/kurbo-0.7.1)
  set(CJ_KURBO_SRC ${CMAKE_CURRENT_SOURCE_DIR}/kurbo)
  set(CJ_KURBO_DIR ${CMAKE_CURRENT_BINARY_DIR}/kurbo)
  configure_file(${CJ_KURBO_SRC}/Cargo.toml.in ${CJ_KURBO_DIR}/Cargo.toml @ONLY)
  configure_file(${CJ_KURBO_SRC}/cargo_config.toml.in ${CJ_KURBO_DIR}/cargo_home/config.toml @ONLY)
  set(CJ_KURBO_LIB ${CJ_KURBO_DIR}/target/release/libcj_bench_kurbo.a)
  add_custom_command(
    OUTPUT ${CJ_KURBO_LIB}
    COMMAND ${CMAKE_COMMAND} -E env CARGO_HOME=${CJ_KURBO_DIR}/cargo_home RUSTC=${CJ_RUSTC}
            ${CJ_CARGO} build --release --offline --quiet --manifest-path ${CJ_KURBO_DIR}/Cargo.toml
            --target-dir ${CJ_KURBO_DIR}/target
    DEPENDS ${CJ_KURBO_SRC}/lib.rs ${CJ_KURBO_DIR}/Cargo.toml
    COMMENT "cargo: kurbo peer for bench_flatten"
    VERBATIM)
  add_custom_target(cj_bench_kurbo_build DEPENDS ${CJ_KURBO_LIB})
  add_library(cj_bench_kurbo STATIC IMPORTED)
  set_target_properties(cj_bench_kurbo PROPERTIES IMPORTED_LOCATION ${CJ_KURBO_LIB})
  add_dependencies(cj_bench_kurbo cj_bench_kurbo_build)
  target_link_libraries(bench_flatten PRIVATE cj_bench_kurbo pthread dl m)
  target_compile_definitions(bench_flatten PRIVATE CJ_HAVE_KURBO=1)
  target_link_libraries(bench_flatten_icount PRIVATE cj_bench_kurbo pthread dl m)
  target_compile_definitions(bench_flatten_icount PRIVATE CJ_HAVE_KURBO=1)
else()
  message(STATUS "cargo or librust-kurbo-dev not found: bench_flatten runs without the kurbo rows")
endif()

# The distance oracle of the peer table (branch and bound in long double).
target_sources(bench_flatten PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/flatten_oracle.c)
