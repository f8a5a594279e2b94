// The table of commands and options (see command_definitions.hpp). Everything the user
// sees about the command line comes from here: the parser refuses what is not in it, and
// the usage, each command's --help, the bash completion and the man page print it.
//
// To add an option: add a line to the command's kXxxOptions array below, e.g.
//     {"ui", 'u', "", "open the browser view of the run"},                          // a flag
//     {"rate", 'r', "HZ", "loop rate", "1 kHz", &option::run_rate},  // a number with unit and range
//     {"hand", 0, "MOTION", "hand motion", "sweep", nullptr, nullptr, "sweep hold none", Completion::values},
// then read it in the command with arguments.take_flag("ui"), take(option::run_rate) or
// take_value("hand"). A numeric option's range lives in option_definitions.hpp and is
// pointed to from here, so the range checked and the range shown are the same object.
// The command refuses (std::logic_error, exit 1) to read an option that is not here, and
// an option here that the command never reads is reported the same way: the table and
// the code cannot disagree silently.
//
// To add a command: write its options array and examples, add a CommandDefinition to
// kCommands (a command with several forms, selected by a flag, gets one entry per form,
// as bench does), and dispatch it in main.cpp.
#include "engine/cli/command_definitions.hpp"

#include <algorithm>
#include <array>

#include "engine/base/errors.hpp"
#include "engine/base/units.hpp"
#include "engine/cli/option_definitions.hpp"

namespace hapscene {
namespace {

using C = Completion;

constexpr std::string_view kHandValues = "sweep hold release shake none line circle";
constexpr std::string_view kScenarioValues = "sweep press release hold shake free swipe";
constexpr std::string_view kPlotScenarioValues = "sweep press release hold shake free line circle";

// ---- run
constexpr OptionDefinition kRunOptions[] = {
    {"device", 'D', "SPEC",
     "the device: sim, a simulated device from the scene's profile; hil, the firmware on a simulated "
     "ATmega328P and Hapkit (2-DOF: two boards as a Hapkit pantograph's joints; hil:FILE.elf: another build); serial:PORT, a Hapkit running the hapscene firmware "
     "(2-DOF: serial:PORT1,PORT2); haply:PORT, a Haply 2DIY",
     "sim", nullptr, nullptr, "sim hil serial: haply:", C::device},
    {"baud", 0, "N", "serial speed in bits per second", "1000000", nullptr, &option::baud},
    {"duration", 'd', "T", "device time per environment", "2 s", &option::duration},
    {"sim-time", 0, "", "run as fast as possible in simulated time instead of real time"},
    {"hand", 0, "MOTION",
     "the simulated hand: sweep, hold, release, shake or none; a 2-DOF run also line and circle", "sweep", nullptr,
     nullptr, kHandValues, C::values},
    {"hand-stiffness", 0, "K", "the hand's grip stiffness", "200 N/m", &option::run_hand_stiffness},
    {"hand-damping", 0, "B", "the hand's damping", "2 N*s/m", &option::run_hand_damping},
    {"hold", 0, "X", "where --hand hold, release and shake hold; 2-DOF: X,Y", "0 m, 2-DOF: the start",
     &option::hold},
    {"release", 0, "T", "when --hand release lets go", "0.5 s", &option::release},
    {"start", 0, "X", "the handle's start position; 2-DOF: X,Y", "0 m, 2-DOF: the profile's home",
     &option::run_start},
    {"noise", 0, "COUNTS", "1-DOF: the sensor noise's standard deviation", "the profile's", &option::noise},
    {"seed", 0, "N", "the sensor noise's seed", "1", nullptr, &option::seed},
    {"quiet", 'q', "", "no live status line"},
    {"no-reload", 0, "", "do not reload the environment when its files change"},
    {"overruns", 0, "stop|report",
     "real time: deadline misses past the limits stop the run with zero force (a fault), or are reported and "
     "the run goes on",
     "stop; sim: report (its world waits for the loop)", nullptr, nullptr, "stop report", C::values},
    {"log", 'l', "FILE.csv", "per-tick telemetry (one environment)", "", nullptr, nullptr, "", C::output},
    {"plot", 'p', "FILE.svg", "the run's figure (one environment)", "", nullptr, nullptr, "", C::output},
    // Its value is optional (`--ui`, `--ui 8080`, `--ui HOST:PORT`): run_command takes it
    // before the others are read (ui_option.hpp), so the parser never sees it.
    {"ui", 0, "[PORT|HOST:PORT]",
     "a live view in the browser: prints its address with an access token (loopback, a free port by default; "
     "the run lasts a day unless --duration says; one environment, real time)"},
};
constexpr std::string_view kRunExamples[] = {
    "run environments/wall.json",
    "run environments/wall.json --sim-time --log wall.csv",
    "run environments/spring.json --hand release --hold 20mm -d 3s",
    "run environments/wall.json -D serial:/dev/ttyACM0",
    "run environments/wall.json --ui",
};

// ---- probe
constexpr OptionDefinition kProbeOptions[] = {
    {"x", 0, "START:STOP:STEP",
     "positions to probe (at most 1000000 points; |STEP| at least 1 nm; required)", "", &option::probe_position},
    {"y", 0, "START:STOP:STEP", "2-DOF: the second axis's positions (required there); x outer, y inner", "",
     &option::probe_position},
    {"v", 0, "V", "the velocity at every point (2-DOF: VX,VY)", "0 m/s", &option::probe_velocity},
    {"t", 0, "T", "the run time each point is evaluated at, from fresh script instances", "0 s",
     &option::probe_time},
};
constexpr std::string_view kProbeExamples[] = {
    "probe environments/wall.json --x -10mm:30mm:1mm",
    "probe environments/texture.json --x 0:0.03:0.0005 --v 0.1",
};

// ---- bench and its forms
constexpr OptionDefinition kBenchOptions[] = {
    {"seconds", 0, "T", "recorded sensor readings per row", "20 s", &option::bench_seconds},
    {"passes", 0, "N", "passes over the readings per row", "10", nullptr, &option::bench_passes},
    {"scripts", 0, "DIR", "where the Lua twins of the lab effects are", "scripts", nullptr, nullptr, "", C::folder},
};
constexpr std::string_view kBenchExamples[] = {
    "bench",
    "bench environments/wall.json --seconds 2 --passes 3",
};
constexpr OptionDefinition kAccuracyOptions[] = {
    {"svg", 0, "FILE.svg", "the figure of the 1-D rows", "", nullptr, nullptr, "", C::output},
    {"rate", 0, "HZ", "only this loop rate: 250, 500, 1000, 2000, 5000, 10000 or 20000 Hz", "all",
     &option::accuracy_rate},
    {"axes", 0, "1|2", "only the Hapkit's rows (1) or the planar plant's (2)", "both", nullptr,
     &option::accuracy_axes, "1 2", C::values},
};
constexpr std::string_view kAccuracyExamples[] = {"bench --accuracy --svg accuracy.svg"};
constexpr OptionDefinition kStressOptions[] = {
    {"noise", 0, "COUNTS", "sensor noise of the sweeps", "0.5 counts", &option::stress_noise},
    {"rate", 0, "HZ", "the damping sweep's loop rate", "1000 Hz", &option::stress_rate},
};
constexpr OptionDefinition kSoakOptions[] = {
    {"ticks", 0, "N", "ticks per environment", "100000000", nullptr, &option::soak_ticks},
    {"scripts", 0, "DIR", "where the Lua twins of the lab effects are", "scripts", nullptr, nullptr, "", C::folder},
    {"no-lua", 0, "", "only the built-in effects, not their Lua twins"},
};
constexpr OptionDefinition kCallgrindOptions[] = {
    {"impl", 0, "IMPL", "what runs: builtin, lua (the Lua twin) or baseline (the hand-written lab code)",
     "builtin", nullptr, nullptr, "builtin lua baseline", C::values},
    {"ticks", 0, "N", "ticks to run", "100000", nullptr, &option::callgrind_ticks},
    {"scripts", 0, "DIR", "where the Lua twins of the lab effects are", "scripts", nullptr, nullptr, "", C::folder},
};
constexpr OptionDefinition kRealtimeOptions[] = {
    {"seconds", 0, "T", "recorded sensor readings per row, ticked at the scene's rate", "1 s", &option::bench_seconds},
    {"scripts", 0, "DIR", "where the Lua twins of the lab effects are", "scripts", nullptr, nullptr, "", C::folder},
};
constexpr std::string_view kRealtimeExamples[] = {"bench --realtime", "bench --realtime environments/wall.json --seconds 5"};
constexpr std::string_view kCallgrindExamples[] = {
    "bench --callgrind environments/wall.json --impl lua --ticks 200000",
};

// ---- validate
constexpr OptionDefinition kValidateOptions[] = {
    {"scenario", 's', "NAMES",
     "scenarios to run, comma-separated: sweep, press, release, hold, shake, free; 2-DOF: sweep, press, swipe, "
     "release, hold, shake, free",
     "all", nullptr, nullptr, kScenarioValues, C::values, true},
    {"hand-stiffness", 0, "K", "the virtual hand's grip stiffness", "200 N/m", &option::hand_stiffness},
    {"hand-damping", 0, "B", "the virtual hand's damping", "2 N*s/m", &option::hand_damping},
    {"hand-mass", 0, "M", "the virtual hand's mass", "20 g", &option::hand_mass},
    {"noise", 0, "COUNTS", "1-DOF: the sensor noise's standard deviation", "the profile's", &option::noise},
    {"seed", 0, "N", "the sensor noise's seed", "1", nullptr, &option::seed},
    {"start", 0, "X", "the free scenario's start; 2-DOF: X,Y", "4 mm, 2-DOF: the profile's home",
     &option::free_start},
    {"report", 'r', "FILE.json", "the JSON report (one environment)", "", nullptr, nullptr, "", C::output},
    {"plot", 'p', "FILE.svg", "the figure (one environment)", "", nullptr, nullptr, "", C::output},
    {"quiet", 'q', "", "one line per environment instead of the summary"},
    {"verbose", 'v', "", "every check of every scenario (default: a line per scenario and the rows of the checks that failed)"},
};
constexpr std::string_view kValidateExamples[] = {
    "validate environments/wall.json",
    "validate environments/wall.json --report wall-report.json --plot wall.svg",
    "validate -q environments/*.json",
};

// ---- devices
constexpr OptionDefinition kDevicesOptions[] = {
    {"json", 0, "", "the list as JSON"},
    {"no-probe", 0, "", "list the ports only, without the handshake (opening a port resets an Uno-style board)"},
    {"timeout", 0, "T", "how long each port has to answer the handshake", "2.5 s", &option::devices_timeout},
    {"baud", 0, "N", "serial speed in bits per second", "1000000", nullptr, &option::baud},
};
constexpr std::string_view kDevicesExamples[] = {"devices", "devices --json --timeout 1s"};

// ---- calibrate
constexpr OptionDefinition kCalibrateOptions[] = {
    {"device", 'D', "SPEC", "serial:PORT (a kit), or sim and hil (the simulated hand plays the user)", "sim", nullptr,
     nullptr, "sim hil serial:", C::device},
    {"profile", 0, "NAME|FILE", "the profile calibrated", "hapkit3", nullptr, nullptr, "", C::json},
    {"output", 'o', "FILE", "the profile written", "NAME-calibrated.json", nullptr, nullptr, "", C::output},
    {"yes", 0, "", "no prompts: each step runs for its time"},
    {"travel-time", 0, "T", "the travel step", "15 s; 4 s on sim and hil", &option::calibrate_travel_time},
    {"pulse-force", 0, "F", "the direction pulse's largest force", "0.5 N", &option::calibrate_pulse_force},
    {"simulated-kit", 0, "FILE", "sim and hil: build the simulated Hapkit from this profile", "", nullptr, nullptr, "",
     C::json},
    {"baud", 0, "N", "serial speed in bits per second", "1000000", nullptr, &option::baud},
};
constexpr std::string_view kCalibrateExamples[] = {"calibrate --device serial:/dev/ttyACM0",
                                                   "calibrate --device hil --yes --output my_hapkit.json"};

// ---- test
constexpr OptionDefinition kTestOptions[] = {
    {"verbose", 'v', "", "print every expectation, not only the unmet ones"},
    {"json", 0, "FILE.json", "every spec's verdict and expectations as JSON (hapscene-test/1)", "", nullptr, nullptr, "",
     C::output},
    {"junit", 0, "FILE.xml", "the same as JUnit XML, for CI servers' test reports", "", nullptr, nullptr, "", C::output},
    {"jobs", 'j', "N", "specs run at once, each in a process of its own (0: one per core)", "1", nullptr,
     &option::test_jobs},
    {"spec-timeout", 0, "T", "stop a spec that runs longer, as failed (runs it in a process of its own)", "none",
     &option::test_spec_timeout},
};
constexpr std::string_view kTestExamples[] = {"test", "test environments/spring.test.json", "test scripts",
                                              "test class/ --jobs 0 --junit results.xml"};

// ---- plot
constexpr OptionDefinition kPlotOptions[] = {
    {"scenario", 's', "NAME",
     "the scenario drawn: sweep, press, release, hold, shake or free; 2-DOF: sweep, press, line or circle",
     "sweep", nullptr, nullptr, kPlotScenarioValues, C::values},
    {"output", 'o', "FILE.svg", "the figure", "the environment file's name with .svg, here", nullptr, nullptr, "", C::output},
    {"hand-stiffness", 0, "K", "the virtual hand's grip stiffness", "200 N/m", &option::hand_stiffness},
    {"hand-damping", 0, "B", "the virtual hand's damping", "2 N*s/m", &option::hand_damping},
    {"hand-mass", 0, "M", "the virtual hand's mass", "20 g", &option::hand_mass},
    {"noise", 0, "COUNTS", "1-DOF: the sensor noise's standard deviation", "the profile's", &option::noise},
    {"seed", 0, "N", "the sensor noise's seed", "1", nullptr, &option::seed},
    {"start", 0, "X", "1-DOF: the free scenario's start", "4 mm", &option::free_start},
    {"grid", 0, "N", "2-DOF: arrows along the workspace's longer side", "24", nullptr, &option::plot_grid},
    {"width", 0, "PX", "2-DOF: the figure's width in pixels", "900", nullptr, &option::plot_width},
};
constexpr std::string_view kPlotExamples[] = {
    "plot environments/spring.json --scenario release --output spring.svg",
};

// ---- new
constexpr OptionDefinition kNewOptions[] = {
    {"device", 'D', "PROFILE", "2-DOF kinds: the planar device (a shipped name or a profile file)", "haplink", nullptr,
     nullptr, "", C::json},
    {"force", 0, "", "overwrite files that exist (default: refuse)"},
};
constexpr std::string_view kNewExamples[] = {"new wall my_wall", "new spec my_wall", "new script bumpy",
                                             "new circle coin --device haply2diy_v3"};

constexpr CommandDefinition kCommands[] = {
    {"run", "", "ENV [ENV...] [options]", "run environments on a device (simulated by default)",
     "Loads every environment first (a bad file stops everything before anything moves), then runs each on the "
     "device, with a live status line on a terminal and a summary at the end. A 2-DOF environment runs alone. "
     "Ctrl-C ends the run at the next tick and still prints the summary; the files are reloaded when they change.",
     kRunOptions, C::environment, kRunExamples},
    {"probe", "", "ENV --x START:STOP:STEP [options]", "print the open-loop force-displacement curve as CSV",
     "Prints x_m,v_m_per_s,force_N,output_N per position (2-DOF: x_m,y_m,vx_m_per_s,vy_m_per_s,force_x_N,"
     "force_y_N,output_x_N,output_y_N per grid point): what the environment asks for, and what the device would "
     "be commanded after the safety rules. A script fault is printed once on stderr and makes the exit code 1.",
     kProbeOptions, C::environment, kProbeExamples},
    {"validate", "", "ENV [ENV...] [options]", "check environments with virtual-hand scenarios",
     "Runs each environment closed loop on the simulated device through the virtual-hand scenarios, in "
     "simulated time, and prints a table of verdicts. Exit 1 when a check fails; each file gets its verdict.",
     kValidateOptions, C::environment, kValidateExamples},
    {"test", "", "[SPEC|FOLDER...] [options]", "run environment test specs",
     "Runs test specs (*.test.json; a folder: every one under it; nothing given: every one under environments/ "
     "and scripts/) and prints PASS or FAIL per spec with each unmet expectation.",
     kTestOptions, C::spec, kTestExamples},
    {"devices", "", "[options]", "serial ports that look like boards, and which answer the handshake",
     "Lists /dev/ttyACM*, /dev/ttyUSB* and /dev/serial/by-id with their USB vendor, product and serial number, "
     "and which of them answer hapscene's handshake, with the firmware version.",
     kDevicesOptions, C::none, kDevicesExamples},
    {"calibrate", "", "--device SPEC [options]", "measure a kit and write a profile that extends the shipped one",
     "Walks through the kit's checks: the sensor's centre, the travel found while the handle is moved across its "
     "range, and the motor's direction with a small, slow, force-limited pulse; writes a profile that extends "
     "the calibrated one and overrides only the keys found to differ.",
     kCalibrateOptions, C::none, kCalibrateExamples},
    {"new", "", "KIND NAME [options]", "start an environment, a script or a test spec from a template",
     "Writes NAME.json, NAME.lua or NAME.test.json (in NAME's folder) from a commented template of KIND: spring, "
     "wall, damper, texture (1-DOF environments), script (a 1-DOF Lua force), box, circle (2-DOF environments), "
     "planar-script (a 2-D Lua force and the environment that runs it), spec (a test spec for NAME.json or "
     "NAME.lua). Every template validates as written; edit it, then validate and run it.",
     kNewOptions, C::none, kNewExamples},
    {"plot", "", "ENV [options]", "draw the force-displacement curve and a scenario as SVG",
     "Draws the force-displacement curve and one scenario's time series as an SVG figure (2-DOF: the force "
     "field, the run's paths and time series per axis).",
     kPlotOptions, C::environment, kPlotExamples},
    {"bench", "", "[ENV...] [options]", "tick cost against the hand-written lab code (1-D and 2-D)",
     "Times the tick of each environment (default: the lab environments and the 2-D rows) next to the "
     "hand-written lab code, and what each part of a scene costs.",
     kBenchOptions, C::environment, kBenchExamples},
    {"bench", "accuracy", "[options]", "simulator run time against error (1-D and 2-D)",
     "Run time against error of the simulated Hapkit for each loop rate, integrator and substep count, then "
     "the 2-D plant's integration error.",
     kAccuracyOptions, C::none, kAccuracyExamples},
    {"bench", "stress", "[options]", "stiffness and damping sweeps",
     "Sweeps stiffness and damping of a wall until the simulated loop goes unstable.", kStressOptions, C::none},
    {"bench", "soak", "[ENV...] [options]", "100 million ticks per lab environment",
     "Runs many simulated ticks of each environment (default: the lab ones and their Lua twins) with the "
     "sweeping hand: non-finite values, drift and memory.",
     kSoakOptions, C::environment},
    {"bench", "realtime", "[ENV...] [options]", "ticks timed the way the real-time loop runs them",
     "Ticks each environment (default: the lab ones and their Lua twins) the way the real-time loop does "
     "(sleep, wake, tick), with and without warming the working set before each deadline, beside the hot "
     "figures: p50 and p99 of the tick's compute, with the goals' verdicts.",
     kRealtimeOptions, C::environment, kRealtimeExamples},
    {"bench", "callgrind", "ENV [options]", "untimed ticks for valgrind --tool=callgrind",
     "Runs a fixed number of ticks of one implementation, untimed, for counting instructions under valgrind.",
     kCallgrindOptions, C::environment, kCallgrindExamples},
};

constexpr BuiltinCommand kBuiltins[] = {
    {"help", "[COMMAND]", "this text, or a command's options"},
    {"version", "", "the version (also --version)"},
    {"completion", "bash", "print the bash completion script"},
    {"man", "[--markdown]", "print the man page (roff; --markdown: the command reference as Markdown)"},
    {"schema", "effects [--markdown]",
     "print the JSON Schema of every built-in effect, written from the engine's declarations (--markdown: the "
     "reference page)"},
};

}  // namespace

std::span<const CommandDefinition> command_definitions() { return kCommands; }

std::span<const BuiltinCommand> builtin_commands() { return kBuiltins; }

std::vector<std::string_view> command_names() {
  std::vector<std::string_view> names;
  for (const CommandDefinition& command : kCommands) {
    if (std::find(names.begin(), names.end(), command.name) == names.end()) names.push_back(command.name);
  }
  for (const BuiltinCommand& builtin : kBuiltins) names.push_back(builtin.name);
  return names;
}

const CommandDefinition* find_command_form(std::string_view command, const std::vector<std::string>& args) {
  const CommandDefinition* chosen = nullptr;
  const CommandDefinition* default_form = nullptr;
  for (const CommandDefinition& form : kCommands) {
    if (form.name != command) continue;
    if (form.mode.empty()) {
      default_form = &form;
      continue;
    }
    const std::string flag = "--" + std::string(form.mode);
    for (const std::string& arg : args) {
      if (arg == "--") break;
      if (arg != flag) continue;
      if (chosen != nullptr && chosen != &form) {
        throw InputError("hapscene " + std::string(command) + ": --" + std::string(chosen->mode) + " and " + flag +
                         " are different forms of the command; give one");
      }
      chosen = &form;
    }
  }
  return chosen != nullptr ? chosen : default_form;
}

// Closer than nearest_name's rule: "frobnicate" is not a typo of "probe" (6 edits).
std::string nearest_command(std::string_view word) {
  const std::string nearest = nearest_name(word, command_names());
  if (nearest.empty()) return nearest;
  const std::size_t distance = edit_distance(word, nearest);
  return distance <= 2 || distance <= word.size() / 3 ? nearest : std::string();
}

}  // namespace hapscene
