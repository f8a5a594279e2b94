// Command-line values: every numeric option is range-checked by its definition, integers
// are read whole, an option given twice says so, and write errors are reported. Exit 2
// for a bad value, 1 for a write that failed.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "engine/base/whole_number.hpp"
#include "tests/cli/cli_support.hpp"
#include "tests/scratch_folder.hpp"

namespace {

using hapscene::test::CliOutcome;
using hapscene::test::run_cli;
using hapscene::read_whole_number;
using hapscene::WholeNumberRead;

// The message of a refused command line (and that it was refused with exit code 2).
std::string refused(const std::string& args) {
  const CliOutcome outcome = run_cli(args);
  CHECK_MESSAGE(outcome.exit_code == 2, args);
  return outcome.err;
}

}  // namespace

TEST_CASE("cli values: out-of-range numbers are refused, naming the option and the range") {
  const std::string env = "environments/wall.json --sim-time --duration 10ms ";
  CHECK(refused("run " + env + "--seed -1") ==
        "error: hapscene run: --seed: expected a whole number in [0, 18446744073709551615], got \"-1\"\n");
  CHECK(refused("run " + env + "--noise -3") == "error: hapscene run: --noise: must be in [0, 1000] counts, got -3 counts\n");
  CHECK(refused("run " + env + "--noise nan") == "error: hapscene run: --noise: value must be finite, got \"nan\"\n");
  CHECK(refused("run environments/wall.json --duration 0") ==
        "error: hapscene run: --duration: must be in (0, 86400] s, got 0 s\n");
  CHECK(refused("run environments/wall.json --duration 25h").starts_with("error: hapscene run: --duration: unknown unit"));
  CHECK(refused("run environments/wall.json --duration '1e400 s'") ==
        "error: hapscene run: --duration: value out of range, got \"1e400 s\"\n");
  CHECK(refused("run " + env + "--hold 5") == "error: hapscene run: --hold: must be in [-1, 1] m, got 5 m\n");
  CHECK(refused("run " + env + "--hand-stiffness -1") ==
        "error: hapscene run: --hand-stiffness: must be in [0, 1000000] N/m, got -1 N/m\n");
  CHECK(refused("run " + env + "--release -1s") == "error: hapscene run: --release: must be in [0, 86400] s, got -1 s\n");
  CHECK(refused("validate environments/wall.json --noise -3") ==
        "error: hapscene validate: --noise: must be in [0, 1000] counts, got -3 counts\n");
  CHECK(refused("validate environments/wall.json --hand-mass 1e9") ==
        "error: hapscene validate: --hand-mass: must be in [0, 10] kg, got 1000000000 kg\n");
  CHECK(refused("plot environments/wall.json --seed 99999999999999999999999") ==
        "error: hapscene plot: --seed: must be in [0, 18446744073709551615], got 99999999999999999999999\n");
  CHECK(refused("bench --stress --rate 1MHz").starts_with("error: hapscene bench: --rate: unknown unit"));
  CHECK(refused("bench --stress --rate 1e6") ==
        "error: hapscene bench: --rate: must be in [100, 100000] Hz, got 1000000 Hz\n");
  CHECK(refused("bench --soak --ticks 5") == "error: hapscene bench: --ticks: must be in [10000, 10000000000], got 5\n");
  CHECK(refused("bench --callgrind environments/wall.json --ticks 1e3") ==
        "error: hapscene bench: --ticks: expected a whole number in [0, 1000000000], got \"1e3\"\n");
  CHECK(refused("probe environments/wall.json --x 0:1:0.1 --v 1e9") ==
        "error: hapscene probe: --v: must be in [-1000, 1000] m/s, got 1000000000 m/s\n");
}

TEST_CASE("cli values: whole numbers are read whole, by one parser") {
  CHECK(refused("bench --passes 10x") ==
        "error: hapscene bench: --passes: expected a whole number in [1, 1000], got \"10x\"\n");
  CHECK(refused("bench --passes ' 10'").find("got \" 10\"") != std::string::npos);
  CHECK(refused("bench --passes +3").find("got \"+3\"") != std::string::npos);
  CHECK(refused("bench --passes 2.5").find("got \"2.5\"") != std::string::npos);
  CHECK(refused("bench --passes ''").find("got \"\"") != std::string::npos);
  CHECK(refused("run environments/wall.json --seed 12abc").find("--seed: expected a whole number") !=
        std::string::npos);
  CHECK(refused("run environments/wall.json --baud 9600.5") ==
        "error: hapscene run: --baud: expected a positive whole number of bits per second in [1, 100000000], got "
        "\"9600.5\"\n");
  // A seed as large as 64 bits holds is fine.
  CHECK(run_cli("run environments/wall.json --sim-time --duration 10ms --seed 18446744073709551615").exit_code == 0);
}

// The engine's one reader of integers from text (the command line and the board process's
// test hook both use it): the whole text or nothing.
TEST_CASE("cli values: read_whole_number takes digits only, the whole text") {
  std::uint64_t value = 42;
  for (const char* bad : {"10x", "7.5", "1e3", "-1", "+3", " 7", "7 ", "", "0x10", "x"}) {
    INFO(bad);
    CHECK(read_whole_number(bad, &value) == WholeNumberRead::not_whole);
  }
  CHECK(value == 42);  // untouched unless ok
  CHECK(read_whole_number("18446744073709551616", &value) == WholeNumberRead::too_large);
  CHECK(read_whole_number("18446744073709551615", &value) == WholeNumberRead::ok);
  CHECK(value == 18446744073709551615ull);
  CHECK(read_whole_number("007", &value) == WholeNumberRead::ok);
  CHECK(value == 7);
  CHECK(refused("run environments/wall.json --seed 7.5").find("--seed: expected a whole number") !=
        std::string::npos);
  CHECK(refused("run environments/wall.json --seed 1e3").find("got \"1e3\"") != std::string::npos);
}

TEST_CASE("cli values: probe ranges refuse non-finite, tiny-step and absurd ranges") {
  CHECK(refused("probe environments/wall.json --x 0.01:0.01:1e-320") ==
        "error: hapscene probe: --x: STEP must be at least 1 nm in size, got 9.999888672e-321 m\n");
  CHECK(refused("probe environments/wall.json --x 0:inf:1") ==
        "error: hapscene probe: --x STOP: value must be finite, got \"inf\"\n");
  CHECK(refused("probe environments/wall.json --x 0:1e400:1") ==
        "error: hapscene probe: --x STOP: value out of range, got \"1e400\"\n");
  CHECK(refused("probe environments/wall.json --x -1e9:0:1") ==
        "error: hapscene probe: --x START: must be in [-1000, 1000] m, got -1000000000 m\n");
  CHECK(refused("probe environments/wall.json --x 0:1000:1e-3") ==
        "error: hapscene probe: --x: more than 1000000 points\n");
  // Every x printed is finite.
  const CliOutcome fine = run_cli("probe environments/wall.json --x 0:2e-9:1e-9");
  CHECK(fine.exit_code == 0);
  CHECK(fine.out == "x_m,v_m_per_s,force_N,output_N\n0,0,0,0\n1e-09,0,0,0\n2e-09,0,0,0\n");
}

TEST_CASE("cli values: an option given twice is reported as given twice") {
  CHECK(refused("run environments/wall.json --seed 1 --seed 2") == "error: hapscene run: --seed is given twice\n");
  CHECK(refused("run environments/wall.json --quiet --quiet") == "error: hapscene run: --quiet is given twice\n");
  CHECK(refused("probe environments/wall.json --x=0:1:0.5 --x 0:2:1") == "error: hapscene probe: --x is given twice\n");
  CHECK(refused("validate environments/wall.json --report a.json --report=b.json") ==
        "error: hapscene validate: --report is given twice\n");
  CHECK(refused("run environments/wall.json --quiet=yes") ==
        "error: hapscene run: --quiet takes no value, got \"--quiet=yes\"\n");
  CHECK(refused("validate environments/wall.json --scenario hold,sweep,hold") ==
        "error: hapscene validate: --scenario: \"hold\" is listed twice\n");
  CHECK(refused("run environments/wall.json --log --colour") ==
        "error: hapscene run: --log needs a value, got the option --colour\n");
  // Still unknown when nobody takes it.
  CHECK(refused("probe environments/wall.json --x 0:1:1 --speed 3 --speed 4") ==
        "error: hapscene probe: unknown option --speed\n");
}

TEST_CASE("cli values: write errors name the file and exit 1") {
  if (!std::filesystem::exists("/dev/full")) return;
  const CliOutcome log = run_cli("run environments/wall.json --sim-time --duration 0.1s --log /dev/full");
  CHECK(log.exit_code == 1);
  CHECK(log.err == "hapscene run: /dev/full: write failed: No space left on device\n");
  CHECK(log.out.find("samples written") == std::string::npos);
  CHECK(log.out.find("  telemetry        FAILED: /dev/full: write failed: No space left on device\n") !=
        std::string::npos);

  const CliOutcome plot = run_cli("run environments/wall.json --sim-time --duration 0.1s --plot /dev/full");
  CHECK(plot.exit_code == 1);
  CHECK(plot.err == "hapscene: /dev/full: write failed: No space left on device\n");
  const CliOutcome report = run_cli("validate environments/wall.json --scenario hold --report /dev/full");
  CHECK(report.exit_code == 1);
  CHECK(report.err == "hapscene: /dev/full: write failed: No space left on device\n");
  const CliOutcome figure = run_cli("plot environments/wall.json --output /dev/full");
  CHECK(figure.exit_code == 1);
  CHECK(figure.err == "hapscene: /dev/full: write failed: No space left on device\n");

  // Standard output: the probe's CSV into a full disk.
  const std::string command = "cd '" HAPSCENE_SOURCE_DIR "' && '" HAPSCENE_BINARY
                              "' probe environments/wall.json --x 0:10mm:1mm >/dev/full 2>/dev/null";
  const int status = std::system(command.c_str());
  CHECK(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 1);
}

TEST_CASE("cli values: run --plot keeps a bounded trace that spans the whole run") {
  const auto svg = std::filesystem::temp_directory_path() / ("hapscene_long_plot_" + std::to_string(getpid()) + ".svg");
  const CliOutcome run = run_cli("run environments/wall.json --sim-time --duration 60s --quiet --plot " + svg.string());
  CHECK(run.exit_code == 0);
  const std::string text = hapscene::test::slurp_file(svg);
  std::filesystem::remove(svg);
  CHECK(text.find("lowest and highest force of every 6 ticks") != std::string::npos);
  CHECK(text.size() < 8'000'000);
}

TEST_CASE("cli values: bench refuses values whose recordings or timings would not fit, before recording") {
  const auto dir = std::filesystem::temp_directory_path();
  const auto fast = dir / ("hapscene_bench_fast_" + std::to_string(getpid()) + ".json");
  const auto medium = dir / ("hapscene_bench_medium_" + std::to_string(getpid()) + ".json");
  std::ofstream(fast) << R"({"rate_hz": "100 kHz", "effects": [{"type": "spring", "stiffness": 100}]})";
  std::ofstream(medium) << R"({"rate_hz": "20 kHz", "effects": [{"type": "spring", "stiffness": 100}]})";
  CHECK(refused("bench --seconds 600 " + fast.string()) ==
        "error: hapscene bench: --seconds 600 x --passes 10 over 1 environment(s) needs about 1223 MiB (readings 231 "
        "MiB, round timings 76 MiB, tail timings 916 MiB), more than the 1024 MiB a bench may use; lower --seconds or "
        "--passes, or give fewer environments\n");
  CHECK(refused("bench --seconds 600 --passes 1000 " + medium.string()).starts_with(
      "error: hapscene bench: --seconds 600 x --passes 1000 over 1 environment(s) needs about 19878 MiB"));
  // The largest values of both ranges over the default rows (the four lab environments,
  // the four 2-D scenes, whose readings are 24 bytes and an index a tick, and the Lua
  // spring's 2-D recording, its two loops and its four force-call loops) are over.
  CHECK(refused("bench --seconds 600 --passes 1000").find("over 8 environment(s) needs about 1225 MiB (readings 92 MiB") !=
        std::string::npos);
  std::filesystem::remove(fast);
  std::filesystem::remove(medium);
}

TEST_CASE("cli: an output file that is an input, another output, a folder or in no folder is refused before the run") {
  const hapscene::test::ScratchFolder folder("outputs");
  const std::string env = folder.write("env.json", R"({"effects": [{"type": "spring", "stiffness": 100}]})").string();
  const auto text_of = [](const std::string& path) {
    std::ostringstream text;
    text << std::ifstream(path).rdbuf();
    return text.str();
  };
  const std::string before = text_of(env);
  const auto onto_input = run_cli("run " + env + " --sim-time --quiet --no-reload --duration 0.1s --log " + env);
  CHECK(onto_input.exit_code == 2);
  CHECK(onto_input.err.find("--log " + env + ": is an input file of this command") != std::string::npos);
  CHECK(text_of(env) == before);
  const std::string out = (folder.dir / "out").string();
  const auto same = run_cli("run " + env + " --sim-time --quiet --no-reload --duration 0.1s --log " + out + " --plot " + out);
  CHECK(same.exit_code == 2);
  CHECK(same.err.find("--plot " + out + ": is also given to --log") != std::string::npos);
  const auto into_folder = run_cli("validate " + env + " --report " + folder.dir.string());
  CHECK(into_folder.exit_code == 2);
  CHECK(into_folder.err.find("is a folder, expected a file name") != std::string::npos);
  const auto nowhere = run_cli("plot " + env + " --output " + (folder.dir / "missing" / "x.svg").string());
  CHECK(nowhere.exit_code == 2);
  CHECK(nowhere.err.find(": no folder ") != std::string::npos);
}
