#!/bin/sh
# Rewrites the golden outputs in tests/golden/data from the built binary. Run it after an
# intended change of output, and commit the result with a message saying why it changed.
# Usage, from anywhere: tests/golden/regenerate.sh [BINARY]  (default: build/hapscene)
set -eu
root=$(cd "$(dirname "$0")/../.." && pwd)
cd "$root"
binary=$(cd "$(dirname "${1:-build/hapscene}")" && pwd)/$(basename "${1:-build/hapscene}")
. tests/golden/golden_cases.sh
fresh=$(mktemp -d)
trap 'rm -rf "$fresh"' EXIT
golden_generate "$binary" "$fresh"
rm -rf tests/golden/data
mkdir -p tests/golden/data
cp -R "$fresh"/. tests/golden/data/
echo "golden: wrote $(find tests/golden/data -type f | wc -l) files, $(du -sb tests/golden/data | cut -f1) bytes, to tests/golden/data"
