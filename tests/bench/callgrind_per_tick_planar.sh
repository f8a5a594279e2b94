#!/bin/sh
# Instructions per tick of the 2-D bench rows (the hand-written 2-D code and the built-in
# scene), counted as tests/bench/callgrind_per_tick.sh counts the 1-D rows (it does the
# work: this is its "planar" set).
# Usage, from the repository root: tests/bench/callgrind_per_tick_planar.sh [build/hapscene]
set -eu
exec "$(dirname "$0")/callgrind_per_tick.sh" "${1:-build/hapscene}" planar
