#!/bin/sh
# The command reference page (docs/reference/options.md) is what `hapscene man --markdown`
# writes from the command table, byte for byte (ctest docs_command_options).
#   sh tests/docs/command_options.sh BINARY           check it (exit 1 when it differs)
#   sh tests/docs/command_options.sh BINARY --write   rewrite it (after a change of the table)
set -eu
mode=check
[ "${2:-}" = --write ] && mode=write
exec sh "$(dirname "$0")/generated_page.sh" "$1" docs/reference/options.md "$mode" man --markdown
