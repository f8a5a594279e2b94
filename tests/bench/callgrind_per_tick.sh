#!/bin/sh
# Instructions per tick of every lab environment (hand-written baseline, built-in JSON
# effects, Lua script) counted by valgrind's callgrind, for machines without performance
# counters. Each figure is (Ir(N2 ticks) - Ir(N1 ticks)) / (N2 - N1): the set-up (loading,
# recording the sensor readings, starting Lua) is the same in both runs and cancels.
# Usage, from the repository root: tests/bench/callgrind_per_tick.sh [build/hapscene]
set -eu
hapscene=${1:-build/hapscene}
n1=20000
n2=120000
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

instructions() {  # impl env ticks -> total instructions (Ir) of the whole run
  valgrind --tool=callgrind --callgrind-out-file="$out/cg" "$hapscene" bench --callgrind \
    --impl "$1" --ticks "$3" "$2" >/dev/null 2>&1
  sed -n 's/^summary: *\([0-9]*\).*/\1/p' "$out/cg"
}

printf '%-10s %-10s %14s\n' environment impl instr_per_tick
for env in spring wall damper texture; do
  for impl in baseline builtin lua; do
    a=$(instructions "$impl" "environments/$env.json" $n1)
    b=$(instructions "$impl" "environments/$env.json" $n2)
    printf '%-10s %-10s %14.1f\n' "$env" "$impl" "$(echo "($b - $a) / ($n2 - $n1)" | bc -l)"
  done
done
