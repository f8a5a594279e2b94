#!/bin/sh
# Instructions per tick of the 2-D bench rows (the hand-written 2-D code and the built-in
# scene) counted by valgrind's callgrind, as tests/bench/callgrind_per_tick.sh does for
# the 1-D rows: (Ir(N2 ticks) - Ir(N1 ticks)) / (N2 - N1), so loading and recording the
# simulated run's readings cancel. Then the Lua spring in 1-D (environments/spring.json)
# and in 2-D (the bench's spring_lua_2d: 100 N/m at the middle of the Haplink's workspace,
# the twin of a built-in 2-D spring), and that built-in spring.
# Usage, from the repository root: tests/bench/callgrind_per_tick_planar.sh [build/hapscene]
set -eu
hapscene=${1:-build/hapscene}
n1=5000
n2=25000
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

instructions() {  # impl env ticks -> total instructions (Ir) of the whole run
  valgrind --tool=callgrind --callgrind-out-file="$out/cg" "$hapscene" bench --callgrind \
    --impl "$1" --ticks "$3" "$2" >/dev/null 2>&1
  sed -n 's/^summary: *\([0-9]*\).*/\1/p' "$out/cg"
}

row() {  # name impl env
  a=$(instructions "$2" "$3" $n1)
  b=$(instructions "$2" "$3" $n2)
  printf '%-24s %-10s %14.1f\n' "$1" "$2" "$(echo "($b - $a) / ($n2 - $n1)" | bc -l)"
}

printf '%-24s %-10s %14s\n' environment impl instr_per_tick
for env in haplink_box_inside haply2diy_v3_box_inside haplink_circle_outside; do
  for impl in baseline builtin; do
    [ "$env" = haplink_circle_outside ] && [ "$impl" = baseline ] && continue
    row "$env" "$impl" "environments/planar/$env.json"
  done
done
printf '{"name": "spring_2d", "device": "haplink", "effects": [{"type": "spring", "stiffness": "100 N/m", "center": ["-15 mm", "127.5 mm"]}]}\n' \
  >"$out/spring_2d.json"
row "spring (1-D)" lua environments/spring.json
row spring_2d lua "$out/spring_2d.json"
row spring_2d builtin "$out/spring_2d.json"
