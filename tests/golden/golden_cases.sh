# The golden cases, shared by regenerate.sh and check.sh (sourced, not run).
# Every shipped environment (environments/*.json, not the *.test.json specs nor the device
# profiles in environments/devices/) and every shipped script (scripts/*.lua) is probed
# open loop and run closed loop on the simulated Hapkit; each command's CSV is one file
# under OUTDIR, named after the source file and the case.
# Run from the repository root: the sources are named by relative paths.

# Probe grid: the Hapkit workspace (-50 mm to 45 mm) and 5 mm beyond each end, so the
# zero-outside-the-workspace rule shows too.
golden_probe_x="-55mm:50mm:0.5mm"
# Closed-loop runs, two per source: the default sweeping hand (from 0 towards +40 mm at 80 mm/s:
# 0.4 s covers 0 to 32 mm), and a hand that pulls the handle to -45 mm
# and lets go at 0.2 s, with seeded sensor noise (the negative side, the workspace edge,
# free motion, the noise generator). Both start inside the soft start.
golden_sweep_duration="0.4s"
golden_release_duration="0.3s"

# 2-DOF probe grids: each device family's workspace box and 5 mm beyond, every 5 mm (x outer,
# y inner); one at rest at t = 0 and one moving at (50, -30) mm/s at t = 12.3 ms.
golden_planar_grid() {
  case "$(basename "$1")" in
    haply2diy_v3_*) printf '%s\n' "--x -35mm:73mm:5mm --y 45mm:135mm:5mm" ;;
    *) printf '%s\n' "--x -75mm:45mm:5mm --y 85mm:170mm:5mm" ;;
  esac
}

# golden_not_specs FILE...: the files that are not test specs, one a line.
golden_not_specs() {
  for source in "$@"; do
    case "$source" in
      *.test.json) ;;
      *) printf '%s\n' "$source" ;;
    esac
  done
}

golden_sources() { golden_not_specs environments/*.json scripts/*.lua; }

# golden_generate BINARY OUTDIR: writes every case under OUTDIR. Returns 1 (after trying
# every case) when a probe or a run exits with anything but 0 or leaves no output.
golden_generate() {
  golden_all_status=0
  golden_generate_lab "$1" "$2" || golden_all_status=1
  golden_generate_planar "$1" "$2" || golden_all_status=1
  golden_generate_text "$1" "$2" || golden_all_status=1
  return $golden_all_status
}

# The 1-DOF sources: three probes and two runs each.
golden_generate_lab() {
  golden_binary=$1
  golden_out=$2
  golden_status=0
  for source in $(golden_sources); do
    mkdir -p "$golden_out/$(dirname "$source")"
    stem="$golden_out/$source"
    golden_one "$stem.probe-v0.05.csv" "$golden_binary" probe "$source" --x "$golden_probe_x" --v 0.05 || golden_status=1
    golden_one "$stem.probe-v-0.05.csv" "$golden_binary" probe "$source" --x "$golden_probe_x" --v -0.05 || golden_status=1
    golden_one "$stem.probe-v0.05-t12.3ms.csv" "$golden_binary" probe "$source" --x "$golden_probe_x" --v 0.05 --t 12.3ms || golden_status=1
    golden_one "$stem.run-sweep.csv" "$golden_binary" run "$source" --sim-time --no-reload --quiet \
      --duration "$golden_sweep_duration" --log "$stem.run-sweep.csv" || golden_status=1
    golden_one "$stem.run-release.csv" "$golden_binary" run "$source" --sim-time --no-reload --quiet \
      --duration "$golden_release_duration" --hand release --hold -45mm --release 0.2s \
      --noise 1 --seed 7 --log "$stem.run-release.csv" || golden_status=1
  done
  return $golden_status
}

# The 2-DOF environments (environments/planar/*.json, not the specs): two probes and two
# closed-loop runs each (the default sweep, and the hand moving the handle round a circle).
golden_planar_sources() { golden_not_specs environments/planar/*.json; }

golden_generate_planar() {
  golden_binary=$1
  golden_out=$2
  golden_status=0
  for source in $(golden_planar_sources); do
    mkdir -p "$golden_out/$(dirname "$source")"
    stem="$golden_out/$source"
    # shellcheck disable=SC2046 (the grid is words)
    golden_one "$stem.probe-rest.csv" "$golden_binary" probe "$source" $(golden_planar_grid "$source") || golden_status=1
    golden_one "$stem.probe-moving-t12.3ms.csv" "$golden_binary" probe "$source" $(golden_planar_grid "$source") \
      --v 0.05,-0.03 --t 12.3ms || golden_status=1
    golden_one "$stem.run-sweep.csv" "$golden_binary" run "$source" --sim-time --no-reload --quiet \
      --duration "$golden_sweep_duration" --log "$stem.run-sweep.csv" || golden_status=1
    golden_one "$stem.run-circle.csv" "$golden_binary" run "$source" --sim-time --no-reload --quiet \
      --duration "$golden_sweep_duration" --hand circle --log "$stem.run-circle.csv" || golden_status=1
  done
  return $golden_status
}

# Every command's text: the help of the tool and of each command, the man page and the
# completion; validate's report (JSON, timing fields replaced by "<timing>") and its text for
# every shipped environment and script, 1-D and 2-D; `test` on every shipped spec; and the
# errors for the bad files in tests/golden/bad. Each is one .txt file: stdout, stderr and
# the exit code (a wrong exit code is a difference, not a failure to run).
golden_commands="run probe validate test devices calibrate plot bench version help man completion"

golden_generate_text() {
  golden_binary=$1
  golden_out=$2
  mkdir -p "$golden_out/commands" "$golden_out/validate" "$golden_out/errors"
  golden_text "$golden_out/commands/help.txt" "$golden_binary" help
  golden_text "$golden_out/commands/no-arguments.txt" "$golden_binary"
  for command in $golden_commands; do
    golden_text "$golden_out/commands/help-$command.txt" "$golden_binary" "$command" --help
  done
  golden_text "$golden_out/commands/man.txt" "$golden_binary" man
  golden_text "$golden_out/commands/completion-bash.txt" "$golden_binary" completion bash
  golden_text "$golden_out/commands/test-all.txt" "$golden_binary" test --verbose
  for source in $(golden_sources) $(golden_planar_sources); do
    report="$golden_out/validate/$(printf '%s' "$source" | tr / _).report.json"
    golden_text "$golden_out/validate/$(printf '%s' "$source" | tr / _).txt" \
      "$golden_binary" validate "$source" --report "$report"
    golden_untimed_report "$report"
  done
  for bad in tests/golden/bad/*; do
    golden_text "$golden_out/errors/$(basename "$bad").txt" "$golden_binary" validate "$bad"
  done
}

# golden_text OUTFILE COMMAND...: the command's stdout, stderr and exit code in one file,
# with the tick compute times validate prints (machine-dependent) replaced by "<timing>".
golden_text() {
  golden_file=$1
  shift
  golden_rc=0
  "$@" >"$golden_file.out" 2>"$golden_file.err" || golden_rc=$?
  {
    # The command as a user types it: no binary path, output files named from OUTDIR.
    printf '$ hapscene%s\n' "${*#"$1"}" | sed "s|${golden_out:?}/|OUTDIR/|g"
    echo "--- stdout"
    golden_untimed_text <"$golden_file.out"
    echo "--- stderr"
    golden_untimed_text <"$golden_file.err"
    echo "--- exit code $golden_rc"
  } >"$golden_file"
  rm -f "$golden_file.out" "$golden_file.err"
}

golden_untimed_text() {
  sed -E 's/p50 [0-9.]+ us, p99 [0-9.]+ us, max [0-9.]+ us/p50 <timing>, p99 <timing>, max <timing>/g'
}

# A validate report without its timing fields: tick_compute_s, and the tick_compute
# check's value, detail and verdict (the check's name and threshold stay).
golden_untimed_report() {
  [ -f "$1" ] || return 0
  /usr/bin/python3 - "$1" <<'PY'
import json, sys
path = sys.argv[1]
with open(path) as f:
    report = json.load(f)
def untime(node):
    if isinstance(node, dict):
        if "tick_compute_s" in node:
            node["tick_compute_s"] = "<timing>"
        if node.get("name") == "tick_compute" and "verdict" in node:
            for key in ("value", "detail", "pass", "verdict"):
                node[key] = "<timing>"
        for value in node.values():
            untime(value)
    elif isinstance(node, list):
        for value in node:
            untime(value)
untime(report)
with open(path, "w") as f:
    json.dump(report, f, indent=1, sort_keys=True)
    f.write("\n")
PY
}

# golden_one OUTFILE COMMAND...: a probe's CSV is its stdout; a run writes OUTFILE itself
# (--log) and its stdout, the summary with timings and paths, is not kept.
golden_one() {
  golden_file=$1
  shift
  case "$2" in
    probe) "$@" >"$golden_file" 2>"$golden_file.err" ;;
    *) "$@" >/dev/null 2>"$golden_file.err" ;;
  esac
  golden_rc=$?
  if [ $golden_rc -ne 0 ] || [ ! -s "$golden_file" ]; then
    echo "golden: exit code $golden_rc from: $*" >&2
    cat "$golden_file.err" >&2
    rm -f "$golden_file" "$golden_file.err"
    return 1
  fi
  rm -f "$golden_file.err"
}
