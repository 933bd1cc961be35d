#!/bin/sh
# Instruction counts of the tessellation rows of issue 19 (bench_tess_live under callgrind: only
# the measured call is collected). Usage: bench/tess_callgrind.sh path/to/bench_tess_live
set -e
B=${1:-build/bench/bench_tess_live}
count() { # prints the collected instruction count of one run
    out=$(mktemp)
    valgrind --tool=callgrind --collect-atstart=no --callgrind-out-file="$out" "$@" >/dev/null 2>&1
    awk '/^summary:/ {print $2}' "$out"
    rm -f "$out"
}
echo "cold teapot at 0.25 px: $(count "$B" cold) instructions"
for m in "teapot 0.0010335430324191963" "sphere 1e-4" "torus 2.5e-4"; do
    set -- $m
    a=$(count "$B" one "$1" adaptive "$2")
    u=$(count "$B" one "$1" uniform "$2")
    echo "$1 tol $2: adaptive $a, uniform $u instructions, ratio $(awk "BEGIN {printf \"%.3f\", $a / $u}")"
done
if "$B" drag 0 >/dev/null 2>&1; then
    echo "drag an interior control point, one frame: $(count "$B" drag 0) instructions"
    echo "drag a shared corner (with its copies), one frame: $(count "$B" drag 1) instructions"
fi
