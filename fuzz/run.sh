#!/bin/sh
# Runs every libFuzzer target in a build configured with -DCJ_FUZZ=ON (see CMakeLists.txt here)
# for SECONDS each (default 20) on a copy of the seed corpus, and prints each target's
# executions. A crash stops the run (exit status 1) and leaves the reproducer in the current
# folder (crash-<sha1>), replayable with `<build>/fuzz/<target> crash-<sha1>`.
#   fuzz/run.sh BUILD_DIR [SECONDS] [JOBS]
# Longer runs: fuzz/run.sh build-fuzz 3600, or run one target by hand:
#   build-fuzz/fuzz/fuzz_plot_json -dict=fuzz/plot_json.dict -max_total_time=36000 \
#       -rss_limit_mb=4096 my_corpus/ fuzz/corpus/plot_json/
set -eu
cd "$(dirname "$0")/.."
BUILD="${1:?usage: fuzz/run.sh BUILD_DIR [SECONDS]}"
SECS="${2:-20}"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
status=0
for t in cli bpt plot_json scene_json mesh_read anim_json checkpoint image; do
    exe="$BUILD/fuzz/fuzz_$t"
    [ -x "$exe" ] || { echo "fuzz: $exe not built, skipped"; continue; }
    seeds="fuzz/corpus/$t"
    dict="fuzz/$t.dict"
    [ "$t" = mesh_read ] && seeds=fuzz/corpus/mesh && dict=fuzz/mesh.dict
    dict_opt="-dict=$dict"
    [ -f "$dict" ] || dict_opt=
    # OpenImageIO (not instrumented, opened by fuzz_image) keeps per-thread message strings
    # that LeakSanitizer reports at exit: leaks are not checked for that target.
    asan="${ASAN_OPTIONS:-}"
    [ "$t" = image ] && asan="${asan:+$asan:}detect_leaks=0"
    mkdir -p "$WORK/$t"
    # shellcheck disable=SC2086 # dict_opt is one word or none
    if ASAN_OPTIONS="$asan" "$exe" $dict_opt -max_total_time="$SECS" -rss_limit_mb=2560 -timeout=30 \
        -print_final_stats=1 "$WORK/$t" "$seeds" >"$WORK/$t.log" 2>&1; then
        runs=$(sed -n 's/^stat::number_of_executed_units: *\([0-9]*\).*/\1/p' "$WORK/$t.log")
        echo "fuzz: $t: $runs executions in ${SECS} s, no crash"
    else
        echo "fuzz: $t FAILED:"
        tail -40 "$WORK/$t.log"
        status=1
    fi
done
exit $status
