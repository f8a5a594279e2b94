#!/bin/sh
# Instructions per tick counted by valgrind's callgrind, for machines without performance
# counters. Each figure is (Ir(N2 ticks) - Ir(N1 ticks)) / (N2 - N1): the set-up (loading,
# recording the sensor readings, starting Lua) is the same in both runs and cancels.
#   1-D (default): every lab environment, hand-written baseline, built-in JSON effects and
#                  Lua script;
#   planar:        the 2-D bench rows, the hand-written 2-D code and the built-in scene
#                  (tests/bench/callgrind_per_tick_planar.sh runs this).
# Usage, from the repository root: tests/bench/callgrind_per_tick.sh [build/hapscene [planar]]
set -eu
hapscene=${1:-build/hapscene}
set=${2:-1d}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

instructions() {  # impl env ticks -> total instructions (Ir) of the whole run
  valgrind --tool=callgrind --callgrind-out-file="$out/cg" "$hapscene" bench --callgrind \
    --impl "$1" --ticks "$3" "$2" >/dev/null 2>&1
  sed -n 's/^summary: *\([0-9]*\).*/\1/p' "$out/cg"
}

case $set in
  1d)
    n1=20000 n2=120000 width=10
    rows="spring:baseline spring:builtin spring:lua wall:baseline wall:builtin wall:lua
          damper:baseline damper:builtin damper:lua texture:baseline texture:builtin texture:lua"
    dir=environments ;;
  planar)
    n1=5000 n2=25000 width=24
    rows="haplink_box_inside:baseline haplink_box_inside:builtin haply2diy_v3_box_inside:baseline
          haply2diy_v3_box_inside:builtin haplink_circle_outside:builtin"
    dir=environments/planar ;;
  *) echo "usage: $0 [HAPSCENE [planar]]" >&2; exit 2 ;;
esac

printf "%-${width}s %-10s %14s\n" environment impl instr_per_tick
for row in $rows; do
  env=${row%%:*} impl=${row#*:}
  a=$(instructions "$impl" "$dir/$env.json" $n1)
  b=$(instructions "$impl" "$dir/$env.json" $n2)
  printf "%-${width}s %-10s %14.1f\n" "$env" "$impl" "$(echo "($b - $a) / ($n2 - $n1)" | bc -l)"
done
