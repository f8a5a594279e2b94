#!/bin/sh
# The install tree (ctest install_tree): `cmake --install BUILD --prefix P` into a scratch
# prefix, then the installed hapscene run from a folder outside the source and build trees:
# a device profile by name (1-D and planar), a shipped environment (one with a script found
# by a relative path), `test` on installed specs, a validate report, and `--device hil` with
# the installed board and firmware when this build has them (an installed hapscene never
# looks in the build folder, so this proves the installed ones are found).
#   sh tests/install/check_install.sh BUILD_DIR
set -eu
build=$1
scratch=$(mktemp -d "${TMPDIR:-/tmp}/hapscene_install.XXXXXX")
trap 'rm -rf "$scratch"' EXIT INT TERM
prefix=$scratch/prefix
work=$scratch/work
mkdir -p "$work"
fail() { echo "install_tree: FAIL: $*"; exit 1; }

cmake --install "$build" --prefix "$prefix" > "$scratch/install.log" || { cat "$scratch/install.log"; fail "cmake --install"; }
hapscene=$prefix/bin/hapscene
share=$prefix/share/hapscene
for file in "$hapscene" "$share/environments/wall.json" "$share/environments/devices/hapkit3.json" \
            "$share/environments/planar/haplink_box_inside.json" "$share/scripts/spring.lua" \
            "$share/scripts/planar/box.lua" "$share/schemas/environment.schema.json" \
            "$share/schemas/device-profile.schema.json" "$share/schemas/test-spec.schema.json" \
            "$share/schemas/validate-report.schema.json" "$prefix/share/doc/hapscene/README.md" \
            "$prefix/share/doc/hapscene/LICENSE" "$prefix/share/doc/hapscene/CHANGELOG.md"; do
  [ -f "$file" ] || fail "not installed: ${file#"$prefix"/}"
done
[ ! -e "$share/schemas/generate_schemas.py" ] || fail "the schema generator is installed (a source file)"

cd "$work"
# A device profile by name, from a folder with no environments/devices in it.
printf '%s\n' '{"device": "hapkit3", "effects": [{"type": "spring", "stiffness": "100 N/m"}]}' > spring.json
"$hapscene" probe spring.json --x 10mm:10mm:1mm > probe.csv || fail "probe of a hapkit3 scene"
grep -q '^0.01,0,-1,-1$' probe.csv || fail "probe of a hapkit3 scene printed: $(cat probe.csv)"
printf '%s\n' '{"device": "haplink", "effects": [{"type": "spring", "stiffness": "100 N/m", "center": ["0 mm", "120 mm"]}]}' > field.json
"$hapscene" probe field.json --x 10mm:10mm:1mm --y 120mm:120mm:1mm > field.csv || fail "probe of a haplink scene"

# Shipped environments, found through the install tree.
"$hapscene" run "$share/environments/wall.json" --sim-time --duration 0.5s --quiet > run.txt || fail "run wall.json"
"$hapscene" probe "$share/environments/planar/haplink_script_box_inside.json" --x -20mm:-20mm:1mm \
  --y 111mm:111mm:1mm > box.csv || fail "probe of a shipped scene with a script at ../../scripts"
"$hapscene" validate "$share/environments/damper.json" --quiet --report report.json > /dev/null ||
  fail "validate damper.json"
[ -s report.json ] || fail "validate wrote no report"

# test on installed specs: a folder (every *.test.json under it) and one spec.
"$hapscene" test "$share/scripts" > test.txt || { cat test.txt; fail "test $share/scripts"; }
"$hapscene" test "$share/environments/wall.test.json" > test1.txt || { cat test1.txt; fail "test wall.test.json"; }
specs=$(grep -c '^PASS' test.txt || true)
[ "$specs" -ge 10 ] || fail "test $share/scripts passed $specs specs"

# --device hil with the installed board simulator and firmware.
if [ -x "$build/hapscene-board" ]; then
  [ -x "$prefix/libexec/hapscene/hapscene-board" ] || fail "hapscene-board not installed"
  [ -f "$share/firmware/hapkit_firmware.elf" ] && [ -f "$share/firmware/hapkit_firmware.hex" ] ||
    fail "the firmware is not installed"
  "$hapscene" run "$share/environments/wall.json" --device hil --sim-time --duration 0.2s --quiet > hil.txt 2>&1 ||
    { cat hil.txt; fail "run --device hil from the install tree"; }
  # Moved whole, the tree still works: every lookup is relative to the executable.
  mv "$prefix" "$scratch/moved"
  "$scratch/moved/bin/hapscene" run "$scratch/moved/share/hapscene/environments/wall.json" --device hil --sim-time \
    --duration 0.1s --quiet > hil2.txt 2>&1 || { cat hil2.txt; fail "run --device hil from a moved install tree"; }
  echo "install_tree: installed hapscene ran a profile by name, shipped scenes, test on $specs installed specs and --device hil"
else
  echo "install_tree: installed hapscene ran a profile by name, shipped scenes and test on $specs installed specs (no hil in this build)"
fi
