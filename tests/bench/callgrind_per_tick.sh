#!/bin/sh
# Instructions per tick counted by valgrind's callgrind, for machines without performance
# counters. Each figure is (Ir(N2 ticks) - Ir(N1 ticks)) / (N2 - N1): the set-up (loading,
# recording the sensor readings, starting Lua) is the same in both runs and cancels.
#   1-D (default): every lab environment, hand-written baseline, built-in JSON effects and
#                  Lua script;
#   planar:        the 2-D bench rows, the hand-written 2-D code and the built-in scene,
#                  then the Lua spring in 1-D (environments/spring.json) and in 2-D (the
#                  bench's spring_lua_2d: 100 N/m at the middle of the Haplink's workspace,
#                  the twin of a built-in 2-D spring), and that built-in spring
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

# Rows are NAME:IMPL:ENVIRONMENT.
case $set in
  1d)
    n1=20000 n2=120000 width=10 rows=""
    for env in spring wall damper texture; do
      for impl in baseline builtin lua; do rows="$rows $env:$impl:environments/$env.json"; done
    done ;;
  planar)
    n1=5000 n2=25000 width=24
    printf '{"name": "spring_2d", "device": "haplink", "effects": [{"type": "spring", "stiffness": "100 N/m", "center": ["-15 mm", "127.5 mm"]}]}\n' \
      >"$out/spring_2d.json"
    rows="haplink_box_inside:baseline haplink_box_inside:builtin haply2diy_v3_box_inside:baseline
          haply2diy_v3_box_inside:builtin haplink_circle_outside:builtin"
    rows=$(for row in $rows; do echo "$row:environments/planar/${row%%:*}.json"; done)
    rows="$rows spring_(1-D):lua:environments/spring.json spring_2d:lua:$out/spring_2d.json
          spring_2d:builtin:$out/spring_2d.json" ;;
  *) echo "usage: $0 [HAPSCENE [planar]]" >&2; exit 2 ;;
esac

printf "%-${width}s %-10s %14s\n" environment impl instr_per_tick
for row in $rows; do
  name=${row%%:*} rest=${row#*:}
  impl=${rest%%:*} env=${rest#*:}
  a=$(instructions "$impl" "$env" $n1)
  b=$(instructions "$impl" "$env" $n2)
  printf "%-${width}s %-10s %14.1f\n" "$name" "$impl" "$(echo "($b - $a) / ($n2 - $n1)" | bc -l)"
done
