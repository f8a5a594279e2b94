#!/bin/sh
# A documentation page the program writes (ctest docs_command_options, docs_effect_keys):
# the committed page must be what the program prints, byte for byte.
#   sh tests/docs/generated_page.sh BINARY PAGE check|write ARGS...
# PAGE is relative to the source folder; ARGS are the program's arguments that print it.
set -eu
root=$(cd "$(dirname "$0")/../.." && pwd)
binary=$1 page=$2 mode=$3 name=$(basename "$2")
shift 3
fresh=$(mktemp)
trap 'rm -f "$fresh"' EXIT
"$binary" "$@" > "$fresh"
if [ "$mode" = write ]; then
  cp "$fresh" "$root/$page"
  echo "$name: wrote $page"
elif ! cmp -s "$fresh" "$root/$page"; then
  diff "$root/$page" "$fresh" | head -20
  echo "$name: FAIL: $page is not what \`hapscene $*\` prints; run the test's script with --write and commit it"
  exit 1
else
  echo "$name: $page is what \`hapscene $*\` prints"
fi
