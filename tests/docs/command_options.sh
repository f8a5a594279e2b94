#!/bin/sh
# The command reference page (docs/reference/options.md) is what `hapscene man --markdown`
# writes from the command table, byte for byte (ctest docs_command_options).
#   sh tests/docs/command_options.sh BINARY           check it (exit 1 when it differs)
#   sh tests/docs/command_options.sh BINARY --write   rewrite it (after a change of the table)
set -eu
root=$(cd "$(dirname "$0")/../.." && pwd)
page=$root/docs/reference/options.md
fresh=$(mktemp)
trap 'rm -f "$fresh"' EXIT
"$1" man --markdown > "$fresh"
if [ "${2:-}" = --write ]; then
  cp "$fresh" "$page"
  echo "docs_command_options: wrote $page"
elif ! cmp -s "$fresh" "$page"; then
  diff "$page" "$fresh" | head -20
  echo "docs_command_options: FAIL: docs/reference/options.md is not what the program says;" \
       "run sh tests/docs/command_options.sh build/hapscene --write and commit it"
  exit 1
else
  echo "docs_command_options: docs/reference/options.md is what the program says"
fi
