// The command line describes itself from one table (engine/cli/command_definitions.cpp):
// `CMD --help` and `help CMD`, the top-level usage, --version, "did you mean" for a
// mistyped command or option, short forms, "--duration 3 s", an option given twice, the
// bash completion script (driven in bash) and the man page (rendered by groff).
#include <doctest/doctest.h>

#include <cstdlib>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include "tests/cli/cli_support.hpp"
#include "tests/scratch_folder.hpp"

namespace {

using hapscene::test::CliOutcome;
using hapscene::test::run_cli;

constexpr const char* kCommands[] = {"run", "probe", "validate", "test", "plot", "bench", "devices", "calibrate"};

bool contains(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

// The options the completion script offers for `command` (its opts="..." line), which is
// what the parser accepts: both come from the same table.
std::set<std::string> completion_options(const std::string& script, const std::string& command) {
  const std::size_t branch = script.find("\n        " + command + ")\n");
  REQUIRE(branch != std::string::npos);
  const std::size_t begin = script.find("opts=\"", branch) + 6;
  const std::size_t end = script.find('"', begin);
  std::set<std::string> names;
  std::istringstream words(script.substr(begin, end - begin));
  for (std::string word; words >> word;) names.insert(word);
  return names;
}

// Runs `script` in bash (from the source directory) and returns its standard output.
std::string run_bash(const hapscene::test::ScratchFolder& folder, const std::string& script) {
  const std::string path = folder.write("drive.sh", script).string();
  const std::string out = (folder.dir / "out").string();
  const std::string command = "cd '" HAPSCENE_SOURCE_DIR "' && bash '" + path + "' >'" + out + "' 2>&1";
  CHECK(std::system(command.c_str()) == 0);
  return hapscene::test::slurp_file(out);
}

// The completions bash would offer for `line` (the cursor at its end).
std::string complete(const hapscene::test::ScratchFolder& folder, const std::string& completion_file,
                     const std::string& line) {
  return run_bash(folder, "source '" + completion_file + "'\nCOMP_LINE='" + line +
                              "'\nCOMP_POINT=${#COMP_LINE}\nread -r -a COMP_WORDS <<<\"$COMP_LINE\"\n"
                              "[[ $COMP_LINE == *' ' ]] && COMP_WORDS+=('')\nCOMP_CWORD=$((${#COMP_WORDS[@]} - 1))\n"
                              "_hapscene\nfor reply in \"${COMPREPLY[@]}\"; do printf '%s\\n' \"$reply\"; done\n");
}

}  // namespace

TEST_CASE("command line: CMD --help, CMD -h and help CMD print the command's options, defaults, units and examples") {
  for (const char* command : kCommands) {
    CAPTURE(command);
    const CliOutcome help = run_cli(std::string(command) + " --help");
    CHECK(help.exit_code == 0);
    CHECK(help.err.empty());
    CHECK(help.out.starts_with(std::string("usage: hapscene ") + command));
    CHECK(run_cli(std::string("help ") + command).out == help.out);
    CHECK(run_cli(std::string(command) + " -h").out == help.out);
    CHECK(run_cli(std::string("--help ") + command).out == help.out);
    // Help wins over anything else on the line, even a mistake.
    CHECK(run_cli(std::string(command) + " --bogus --help").out == help.out);
  }
  const std::string run = run_cli("run --help").out;
  CHECK(contains(run, "  -d, --duration T          device time per environment (default 2 s; range (0, 86400] s)\n"));
  CHECK(contains(run, "  -q, --quiet "));
  CHECK(contains(run, "      --hand MOTION "));
  CHECK(contains(run, "examples:\n  hapscene run environments/wall.json\n"));
  const std::string bench = run_cli("help bench").out;
  for (const char* option : {"--scripts DIR", "--no-lua", "--rate HZ", "--seconds T", "--ticks N", "--impl IMPL",
                             "--axes 1|2", "--svg FILE.svg"}) {
    CAPTURE(option);
    CHECK(contains(bench, option));
  }
  // Each form of bench: its own options, ranges and defaults.
  CHECK(contains(bench, "usage: hapscene bench [ENV...] [options]\n       hapscene bench --accuracy [options]\n"));
  CHECK(contains(bench, "options of --soak:\n"));
  CHECK(contains(bench, "--ticks N             ticks per environment (default 100000000; range [10000, 10000000000])"));
  CHECK(contains(bench, "--ticks N             ticks to run (default 100000; range [0, 1000000000])"));
}

TEST_CASE("command line: the usage lists every command and every option the parser accepts") {
  const CliOutcome usage = run_cli("--help");
  CHECK(usage.exit_code == 0);
  CHECK(run_cli("help").out == usage.out);
  CHECK(run_cli("-h").out == usage.out);
  CHECK(run_cli("help completion").out == usage.out);
  CHECK(run_cli("help run validate").exit_code == 2);
  // Without a command: the usage on stderr, exit 2.
  const CliOutcome none = run_cli("");
  CHECK(none.exit_code == 2);
  CHECK(none.err == usage.out);
  // The options missing from the old hand-written usage.
  for (const char* option : {"--scripts", "--no-lua", "--rate", "--axes", "--t T", "--y ", "--grid", "--width"}) {
    CAPTURE(option);
    CHECK(contains(usage.out, option));
  }
  // Every option of every command, as the completion script has them (the parser's table).
  const std::string script = run_cli("completion bash").out;
  const std::string man = run_cli("man").out;
  for (const char* command : kCommands) {
    const std::string help = run_cli(std::string("help ") + command).out;
    for (const std::string& option : completion_options(script, command)) {
      CAPTURE(command);
      CAPTURE(option);
      CHECK(contains(help, option));
      if (option != "--help") {
        CHECK(contains(usage.out, option));
        std::string in_roff;
        for (const char c : option) in_roff += c == '-' ? std::string("\\-") : std::string(1, c);
        CHECK(contains(man, in_roff));
      }
    }
  }
}

TEST_CASE("command line: --version and version") {
  const CliOutcome version = run_cli("--version");
  CHECK(version.exit_code == 0);
  CHECK(version.out.starts_with("hapscene "));
  CHECK(version.out.size() > 10);
  CHECK(run_cli("version").out == version.out);
  CHECK(run_cli("-V").out == version.out);
  CHECK(run_cli("version extra").exit_code == 2);
}

TEST_CASE("command line: a mistyped command or option gets \"did you mean\"") {
  const CliOutcome command = run_cli("rnu environments/wall.json");
  CHECK(command.exit_code == 2);
  CHECK(command.err == "hapscene: unknown command \"rnu\" (did you mean \"run\"?) (try: hapscene --help)\n");
  const CliOutcome help = run_cli("help valdate");
  CHECK(help.exit_code == 2);
  CHECK(help.err == "error: hapscene help: unknown command \"valdate\" (did you mean \"validate\"?)\n");
  CHECK(run_cli("frobnicate").err == "hapscene: unknown command \"frobnicate\" (try: hapscene --help)\n");

  const CliOutcome option = run_cli("run environments/wall.json --sim-tme");
  CHECK(option.exit_code == 2);
  CHECK(option.err == "error: hapscene run: unknown option --sim-tme (did you mean --sim-time?)\n");
  CHECK(run_cli("validate environments/wall.json --scenaro hold").err ==
        "error: hapscene validate: unknown option --scenaro (did you mean --scenario?)\n");
  CHECK(run_cli("bench --sok").err == "error: hapscene bench: unknown option --sok (did you mean --soak?)\n");
  CHECK(run_cli("run environments/wall.json -z").err == "error: hapscene run: unknown option -z\n");
  // An option of another form of the command says which form it belongs to.
  CHECK(run_cli("bench --stress --seconds 3").err ==
        "error: hapscene bench: unknown option --seconds for hapscene bench --stress (an option of hapscene bench)\n");
  CHECK(run_cli("bench --soak --stress").err ==
        "error: hapscene bench: --stress and --soak are different forms of the command; give one\n");
}

TEST_CASE("command line: short forms are the long options" * doctest::test_suite("threaded")) {
  const hapscene::test::ScratchFolder folder("cli_short_forms");
  const std::string log = (folder.dir / "run.csv").string();
  const CliOutcome run = run_cli("run environments/wall.json --sim-time -q -d 100ms -D sim -l " + log);
  CHECK(run.exit_code == 0);
  CHECK(contains(run.out, "  ticks            100 in 0.100 s of device time"));
  CHECK(contains(run.out, "samples written to " + log));
  // Attached values, and the long name in messages.
  CHECK(run_cli("run environments/wall.json --sim-time -q -d100ms").exit_code == 0);
  CHECK(run_cli("run environments/wall.json -d 0").err == "error: hapscene run: --duration: must be in (0, 86400] s, got 0 s\n");
  CHECK(run_cli("run environments/wall.json -q --quiet").err == "error: hapscene run: --quiet is given twice\n");
  CHECK(run_cli("run environments/wall.json -qd 1s").err ==
        "error: hapscene run: --quiet takes no value, got \"-qd\"\n");
  const CliOutcome quiet = run_cli("validate -q -s hold environments/spring.json");
  CHECK(quiet.exit_code == 0);
  CHECK(quiet.out.starts_with("PASS spring (environments/spring.json): "));
  CHECK(run_cli("test -v environments/spring.test.json").out.find("  ok   ") != std::string::npos);
  // A value that is a short option of the command is a forgotten value.
  CHECK(run_cli("run environments/wall.json --log -q").err ==
        "error: hapscene run: --log needs a value, got the option -q\n");
  // Negative numbers are values, not options.
  CHECK(run_cli("probe environments/wall.json --x -5mm:0:5mm").exit_code == 0);
}

TEST_CASE("command line: \"--duration 3 s\" reads as 3 s, a misspelt unit is named") {
  const CliOutcome spaced = run_cli("run environments/wall.json --sim-time --quiet --duration 300 ms");
  CHECK(spaced.exit_code == 0);
  CHECK(contains(spaced.out, "  ticks            300 in 0.300 s of device time"));
  const CliOutcome probe = run_cli("probe environments/wall.json --x 0:10mm:5mm --v 2 mm/s");
  CHECK(probe.exit_code == 0);
  CHECK(contains(probe.out, "0,0.002,"));
  const CliOutcome misspelt = run_cli("run environments/wall.json --duration 3 sec");
  CHECK(misspelt.exit_code == 2);
  CHECK(contains(misspelt.err, "error: hapscene run: --duration: unknown unit \"sec\""));
  // A file after a number is still a file.
  CHECK(run_cli("run --sim-time --quiet --duration 0.1 environments/wall.json").exit_code == 0);
}

TEST_CASE("command line: an option given twice is refused, naming it, in every spelling") {
  CHECK(run_cli("run environments/wall.json --duration 1s -d 2s").err ==
        "error: hapscene run: --duration is given twice\n");
  CHECK(run_cli("plot environments/wall.json -o a.svg --output=b.svg").err ==
        "error: hapscene plot: --output is given twice\n");
  CHECK(run_cli("bench --soak --soak").err == "error: hapscene bench: --soak is given twice\n");
  CHECK(run_cli("test -v --verbose").exit_code == 2);
  // "--" ends the options: what follows is a file, even with a leading dash.
  CHECK(run_cli("probe --x 0:1:1 -- -nofile.json").err == "error: -nofile.json: cannot open file\n");
}

TEST_CASE("command line: the bash completion script parses and completes commands, options and values") {
  const hapscene::test::ScratchFolder folder("cli_completion");
  const CliOutcome script = run_cli("completion bash");
  CHECK(script.exit_code == 0);
  const std::string file = folder.write("hapscene.bash", script.out).string();
  CHECK(std::system(("bash -n '" + file + "'").c_str()) == 0);
  CHECK(run_cli("completion zsh").exit_code == 2);

  CHECK(complete(folder, file, "hapscene ru") == "run\n");
  CHECK(complete(folder, file, "hapscene va") == "validate\n");
  CHECK(complete(folder, file, "hapscene help pl") == "plot\n");
  CHECK(complete(folder, file, "hapscene run --sim-t") == "--sim-time\n");
  CHECK(complete(folder, file, "hapscene bench --no-") == "--no-lua\n");
  CHECK(complete(folder, file, "hapscene run environments/wall.json --hand re") == "release\n");
  CHECK(complete(folder, file, "hapscene validate --scenario hold,sw") == "hold,sweep\nhold,swipe\n");
  CHECK(complete(folder, file, "hapscene run --device ser") == "serial:\n");
  // A value with units: nothing offered (not file names).
  CHECK(complete(folder, file, "hapscene run --duration ").empty());
  // Environment files: *.json and *.lua and folders, not other files.
  const std::string files = complete(folder, file, "hapscene run environments/w");
  CHECK(contains(files, "environments/wall.json\n"));
  CHECK(!contains(files, ".md"));
  const std::string lua = complete(folder, file, "hapscene probe scripts/spr");
  CHECK(contains(lua, "scripts/spring.lua\n"));
  CHECK(!contains(lua, "spring.test.json"));
  // --name=value: the value after "=" (bash's word starts after it).
  CHECK(complete(folder, file, "hapscene bench --callgrind --impl=l") == "lua\n");
}

TEST_CASE("command line: the man page renders without warnings") {
  const hapscene::test::ScratchFolder folder("cli_man");
  const CliOutcome man = run_cli("man");
  CHECK(man.exit_code == 0);
  CHECK(man.out.starts_with(".TH HAPSCENE 1 "));
  for (const char* section : {".SH NAME\n", ".SH SYNOPSIS\n", ".SH DESCRIPTION\n", ".SH COMMANDS\n",
                              ".SH \"EXIT STATUS\"\n", ".SS \"hapscene bench \\-\\-soak "}) {
    CAPTURE(section);
    CHECK(contains(man.out, section));
  }
  const std::string page = folder.write("hapscene.1", man.out).string();
  if (std::system("command -v groff >/dev/null 2>&1") != 0) return;
  const std::string text = run_bash(folder, "groff -man -Tutf8 -ww -b -z '" + page + "' 2>&1\n");
  CHECK(text.empty());
  // Plain text (no overstrike or escapes): the options as a reader sees them.
  const std::string rendered = run_bash(folder, "groff -man -Tascii -P-cbou '" + page + "'\n");
  CHECK(contains(rendered, "       -d, --duration T\n"));
  CHECK(contains(rendered, "   hapscene bench --soak [ENV...] [options]\n"));
}

// Every option each command's help lists (every form of bench) is read by the command: given
// alone with a valid value and a file that does not exist, the command gets as far as its
// files (exit 2), never to the logic error that an option the table defines and the code
// never reads (or the code reads and the table lacks) would raise (exit 1).
TEST_CASE("command line: every option in the help is one its command reads") {
  const hapscene::test::ScratchFolder folder("cli_every_option");
  const std::string out = folder.dir.string() + "/out";
  const std::map<std::string, std::string> values = {
      {"device", "sim"}, {"baud", "9600"}, {"duration", "1s"}, {"hand", "hold"}, {"hand-stiffness", "100"},
      {"hand-damping", "1"}, {"hand-mass", "0.02"}, {"overruns", "stop"}, {"hold", "0"}, {"release", "1s"}, {"start", "0"},
      {"noise", "0"}, {"seed", "1"}, {"log", out + ".csv"}, {"plot", out + ".svg"}, {"report", out + ".json"},
      {"output", out + ".svg"}, {"svg", out + ".svg"}, {"x", "0:1mm:1mm"}, {"y", "0:1mm:1mm"}, {"v", "0"},
      {"t", "0"}, {"scenario", "hold"}, {"grid", "10"}, {"width", "500"}, {"seconds", "0.1"}, {"passes", "1"},
      {"scripts", "scripts"}, {"rate", "1000"}, {"axes", "1"}, {"ticks", "10000"}, {"impl", "builtin"},
      {"ui", "8080"}, {"timeout", "1s"}, {"profile", "hapkit3"}, {"travel-time", "2s"}, {"pulse-force", "0.5"},
      {"simulated-kit", "nowhere.json"}, {"json", out + ".json"}, {"junit", out + ".xml"}, {"jobs", "2"}, {"spec-timeout", "10s"}};
  std::size_t checked = 0;
  for (const char* command : kCommands) {
    std::istringstream help(run_cli(std::string("help ") + command).out);
    std::string mode;  // the form whose options follow ("options of --soak:")
    bool in_options = false;
    for (std::string line; std::getline(help, line);) {
      if (line.starts_with("options")) {
        in_options = true;
        mode = line.starts_with("options of ") ? line.substr(11, line.size() - 12) : std::string();
        continue;
      }
      if (line.empty()) in_options = false;
      if (!in_options || !line.starts_with("  ")) continue;
      const std::size_t at = line.find("--");
      if (at == std::string::npos || at > 8 || line.substr(at) .starts_with("--help")) continue;
      const std::size_t name_end = line.find(' ', at);
      const std::string name = line.substr(at + 2, name_end - at - 2);
      const bool flag = name_end == std::string::npos || line[name_end + 1] == ' ';
      std::string args = std::string(command) + (mode.empty() ? "" : " " + mode) + " --" + name;
      if (!flag) {
        CAPTURE(name);
        REQUIRE(values.count(name) == 1);
        args += " " + values.at(name);
      }
      args += std::string(" ") + (std::string(command) == "test" ? "nowhere.test.json" : "nowhere.json");
      CAPTURE(args);
      const CliOutcome outcome = run_cli(args);
      CHECK(outcome.exit_code == 2);
      CHECK(outcome.err.find("command_definitions") == std::string::npos);
      ++checked;
    }
  }
  CHECK(checked >= 55);  // 55 when written
}
