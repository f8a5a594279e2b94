#!/bin/sh
# The 10 kHz soak (not part of the suite: it takes the time it says): a lab texture at
# 10 kHz in real time on the simulated Hapkit for DURATION (default 600 s), then the run's
# summary, which gives the deadline misses (per minute) and whether an overrun faulted.
# Exit status: the run's (1 on an overrun fault).
# Usage, from the repository root: tests/bench/soak_10khz.sh [build/hapscene [DURATION]]
set -eu
hapscene=${1:-build/hapscene}
duration=${2:-600s}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
cat >"$out/texture_10khz.json" <<'JSON'
{"name": "texture_10khz", "rate_hz": 10000,
 "effects": [{"type": "texture", "width": "5 mm", "spacing": "5 mm", "damping": "2 N*s/m"}]}
JSON
"$hapscene" run "$out/texture_10khz.json" --duration "$duration" --no-reload --quiet
