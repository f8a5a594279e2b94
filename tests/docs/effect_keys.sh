#!/bin/sh
# The effects' key reference (docs/reference/effects.md) is what `hapscene schema effects
# --markdown` writes from the effects' declarations, byte for byte (ctest docs_effect_keys).
#   sh tests/docs/effect_keys.sh BINARY           check it (exit 1 when it differs)
#   sh tests/docs/effect_keys.sh BINARY --write   rewrite it (after a declaration changed)
set -eu
mode=check
[ "${2:-}" = --write ] && mode=write
exec sh "$(dirname "$0")/generated_page.sh" "$1" docs/reference/effects.md "$mode" schema effects --markdown
