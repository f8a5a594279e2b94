#!/bin/sh
# Re-runs every golden case (golden_cases.sh) with BINARY and compares each CSV byte for
# byte with the committed one in tests/golden/data; on a difference it prints the file and
# its first differing line. Exit 0 when all are identical, 1 otherwise.
# Usage, from anywhere: tests/golden/check.sh [BINARY]  (default: build/hapscene)
set -u
root=$(cd "$(dirname "$0")/../.." && pwd)
cd "$root" || exit 1
binary=$(cd "$(dirname "${1:-build/hapscene}")" && pwd)/$(basename "${1:-build/hapscene}")
. tests/golden/golden_cases.sh
fresh=$(mktemp -d)
trap 'rm -rf "$fresh"' EXIT
status=0
golden_generate "$binary" "$fresh" || status=1

expected=tests/golden/data
compared=0
differing=0
for name in $( (cd "$expected" && find . -type f; cd "$fresh" && find . -type f) | sort -u); do
  name=${name#./}
  compared=$((compared + 1))
  if [ ! -f "$fresh/$name" ]; then
    echo "golden: $name: committed but no longer produced (a source was removed or renamed?)"
    differing=$((differing + 1))
  elif [ ! -f "$expected/$name" ]; then
    echo "golden: $name: produced but not committed (a new environment or script?)"
    differing=$((differing + 1))
  elif ! cmp -s "$expected/$name" "$fresh/$name"; then
    # First differing line: the first line number where the two files disagree.
    line=$(diff "$expected/$name" "$fresh/$name" | sed -n '1s/^\([0-9]*\).*/\1/p')
    echo "golden: $name differs, first at line $line:"
    echo "  committed: $(sed -n "${line}p" "$expected/$name")"
    echo "  now:       $(sed -n "${line}p" "$fresh/$name")"
    differing=$((differing + 1))
  fi
done
if [ $status -ne 0 ]; then
  echo "golden: FAILED: a command above exited with an error or wrote nothing"
fi
if [ $differing -ne 0 ]; then
  echo "golden: FAILED: $differing of $compared files differ. If the change is intended," \
       "run tests/golden/regenerate.sh and commit tests/golden/data with the reason."
fi
if [ $differing -ne 0 ] || [ $status -ne 0 ]; then
  exit 1
fi
echo "golden: all $compared files identical"
