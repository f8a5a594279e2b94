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

golden_sources() {
  for source in environments/*.json scripts/*.lua; do
    case "$source" in
      *.test.json) ;;
      *) printf '%s\n' "$source" ;;
    esac
  done
}

# golden_generate BINARY OUTDIR: writes every case's CSV under OUTDIR. Returns 1 (after
# trying every case) when a command exits with anything but 0 or leaves no output.
golden_generate() {
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
