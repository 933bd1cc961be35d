#!/bin/sh
# Instructions of the flattening workload of docs/flattening.md (issue 20) at each tolerance:
# 200 random curves x 3 repetitions under callgrind, the start-up (N = 0) subtracted.
# Usage: bench/flatten_callgrind.sh path/to/bench_flatten_icount [ours|kurbo] [degree]
set -e
bin=$1
mode=${2:-ours}
deg=${3:-3}
refs() {
    valgrind --tool=callgrind --callgrind-out-file=/dev/null "$bin" "$mode" "$@" 2>&1 |
        awk '/refs/ {gsub(",", "", $NF); print $NF}'
}
zero=$(refs 0 3 "$deg" 0 0)
for ti in 0 1 2; do
    r=$(refs 200 3 "$deg" 0 "$ti")
    printf 'tol%s %sk  ' "$ti" $(((r - zero) / 1000))
done
echo "($mode, degree $deg; tol0/1/2 = 0.01/0.25/1)"
