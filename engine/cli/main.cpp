// The `hapscene` command: dispatch to a subcommand and map errors to exit codes
// (0 success, 2 invalid input, 1 anything else).
#include <cerrno>
#include <cstdio>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/cli/commands.hpp"
#include "engine/cli/output_file.hpp"
#include "engine/cli/standard_output.hpp"

namespace {

constexpr const char* kUsage = R"(hapscene: a data-driven haptic rendering engine

usage:
  hapscene run ENV [ENV...] [options]     run environments on a device (simulated by default)
  hapscene probe ENV --x START:STOP:STEP [--v V]
                                          print the force-displacement curve as CSV
  hapscene bench [ENV...] [--seconds T] [--passes N]
                                          tick cost against the hand-written lab code
                                          (1-D and 2-D: a planar ENV goes to the 2-D table)
  hapscene bench --accuracy [--svg FILE] [--rate HZ] [--axes 1|2]
                                          simulator run time against error (1-D), and
                                          the 2-D plant's integration error
  hapscene bench --stress                 stiffness and damping sweeps
  hapscene bench --soak [--ticks N]       100 million ticks per lab environment
  hapscene bench --callgrind ENV [--impl builtin|lua|baseline] [--ticks N]
                                          untimed ticks for valgrind --tool=callgrind
  hapscene validate ENV [ENV...] [options]
                                          check an environment with virtual-hand scenarios
  hapscene test [SPEC|FOLDER...]          run environment test specs (*.test.json; a folder: all under it)
  hapscene plot ENV [--scenario NAME] [--output FILE.svg]
                                          draw force-displacement and time series as SVG
                                          (2-DOF: the force field, a run's paths and
                                          time series; also --grid N, --width PX)
  hapscene devices [--json] [--no-probe] [--timeout T]
                                          serial ports that look like boards, and which
                                          answer hapscene's handshake (firmware version)
  hapscene calibrate --device SPEC [--profile NAME] [--output FILE] [--yes]
                                          measure a kit (centre, travel, motor direction)
                                          and write a profile that extends the shipped one
  hapscene help | --help                  this text
  hapscene version | --version

run options:
  --device SPEC         sim (default: a simulated Hapkit from the scene's profile),
                        serial:/dev/ttyACM0 (a Hapkit running the hapscene firmware),
                        hil (the firmware on a simulated ATmega328P and Hapkit)
  --baud N              serial speed (default 1000000)
  --duration T          device time per environment (default 2 s; units allowed: "500 ms")
  --sim-time            run as fast as possible in simulated time instead of real time
  --hand MOTION         simulated hand: sweep (default), hold, release, shake, none
  --hand-stiffness K    hand grip stiffness (default 200 N/m)
  --hand-damping B      hand damping (default 2 N*s/m)
  --hold X              hold position for --hand hold and release (default 0 m)
  --release T           when --hand release lets go (default 0.5 s)
  --start X             handle start position (default 0 m)
  --noise COUNTS        sensor noise standard deviation in counts (default: the profile's)
  --seed N              noise seed (default 1)
  --quiet               no live status line
  --no-reload           do not reload the environment when its files change
  --log FILE.csv        per-tick telemetry: t_s,x_m,v_m_per_s,force_N,output_N,duty,direction
  --plot FILE.svg       the run's figure

validate options:
  --scenario NAMES      sweep, press, release, hold, shake, free (comma-separated; default all)
  --hand-stiffness K    --hand-damping B    --hand-mass M    (default 200 N/m, 2 N*s/m, 20 g)
  --noise COUNTS        --seed N            --start X (free scenario start, default 4 mm)
  --report FILE.json    --plot FILE.svg     --quiet (a line per file)
  --verbose             every check of every scenario (default: a line per
                        scenario and the rows of the checks that failed)
  2-DOF: --scenario sweep, press, swipe, release, hold, shake, free; --start X,Y
                        (free scenario start, default the profile's home)

calibrate options:
  --device SPEC         serial:/dev/ttyACM0 (a kit), or sim and hil (the simulated hand
                        plays the user; default sim)
  --profile NAME|FILE   the profile calibrated (default hapkit3)
  --output FILE         the profile written (default NAME-calibrated.json)
  --yes                 no prompts: each step runs for its time
  --travel-time T       the travel step (default 15 s; 4 s on sim and hil)
  --pulse-force F       the direction pulse's largest force (default 0.5 N)
  --simulated-kit FILE  sim and hil: build the simulated Hapkit from this profile
  --baud N              serial speed (default 1000000)

Values take SI numbers or strings with units ("10 mm", "2 kHz"); each numeric option
has a range (README, "Using it"), and a value outside it is invalid input.
Exit codes: 0 success, 2 invalid input (file, arguments), 1 anything else
(validate and test: 1 when a check or expectation fails; any command: 1 when its
output could not be written).
)";

}  // namespace

namespace {

int dispatch(std::vector<std::string> args) {
  if (args.empty() || args[0] == "help" || args[0] == "--help" || args[0] == "-h") {
    if (args.empty()) std::cerr << kUsage;
    else hapscene::write_out(kUsage);
    return args.empty() ? hapscene::kExitInvalidInput : hapscene::kExitOk;
  }
  if (args[0] == "version" || args[0] == "--version") {
    hapscene::write_out(std::string("hapscene ") + HAPSCENE_VERSION + "\n");
    return hapscene::kExitOk;
  }
  const std::string command = args[0];
  args.erase(args.begin());
  try {
    if (command == "run") return hapscene::run_command(args);
    if (command == "probe") return hapscene::probe_command(args);
    if (command == "bench") return hapscene::bench_command(args);
    if (command == "validate") return hapscene::validate_command(args);
    if (command == "plot") return hapscene::plot_command(args);
    if (command == "test") return hapscene::test_command(args);
    if (command == "devices") return hapscene::devices_command(args);
    if (command == "calibrate") return hapscene::calibrate_command(args);
    std::cerr << "hapscene: unknown command \"" << hapscene::printable(command) << "\" (try: hapscene --help)\n";
    return hapscene::kExitInvalidInput;
  } catch (const hapscene::InputError& error) {
    std::cerr << "error: " << hapscene::printable(error.what()) << "\n";
    return hapscene::kExitInvalidInput;
  } catch (const std::exception& error) {
    std::cerr << "hapscene: " << hapscene::printable(error.what()) << "\n";
    return hapscene::kExitFailure;
  }
}

}  // namespace

int main(int argc, char** argv) {
  const int code = dispatch(std::vector<std::string>(argv + 1, argv + argc));
  // Output that never arrived is a failure, not a success: "probe ... > /dev/full" exits 1
  // and says why (the first failed write's errno, kept by engine/cli/standard_output.hpp).
  if (!hapscene::report_stdout_failure()) return code == hapscene::kExitOk ? hapscene::kExitFailure : code;
  return code;
}
