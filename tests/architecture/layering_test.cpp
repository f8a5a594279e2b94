// The folders of the source tree form layers that include only downward (docs/
// explanation/architecture.md). This test reads the #include lines of every source file and fails on
// an include that goes up or sideways, which also rules out cycles between folders.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <string>
#include <vector>

namespace {

// The documented order, from the ground up. A folder may include its own files and those
// of folders of a lower rank; folders of equal rank do not know each other.
const std::map<std::string, int>& engine_layer_ranks() {
  static const std::map<std::string, int> ranks{
      {"protocol", 0},        // wire format, CRC, unwrapping: shared with the firmware
      {"engine/base", 1},     // errors, units, clock, formatting, file and JSON reading
      {"engine/devices", 2},  // device profiles, models, kinematics, simulators, links
      {"engine/lua", 2},      // the script sandbox
      {"engine/effects", 3},  // what an effect sees, the built-in effects, script effects
      {"engine/scene", 4},    // the compiled scene and its tick
      {"engine/load", 5},     // the environment compiler
      {"engine/run", 6},      // the runner, hot reload, telemetry
      {"engine/harness", 7},  // validate, test specs, probe, plots
      {"engine/bench", 8},    // hapscene bench (a library of its own)
      {"engine/serve", 8},    // the live view of `run --ui` (a library of its own)
      {"engine/cli", 9},      // the command line
      {"python", 10},         // the Python module: above the command line, whose code it runs
  };
  return ranks;
}

// The firmware is a separate program: its own folder and the shared protocol only.
const std::vector<std::string>& firmware_may_include() {
  static const std::vector<std::string> folders{"firmware", "protocol"};
  return folders;
}

struct Include {
  std::string file;      // "engine/scene/step.cpp"
  int line{};
  std::string included;  // "engine/base/errors.hpp"
};

// The layer a path belongs to: "engine/devices/hil/x.cpp" -> "engine/devices".
std::string folder_of(const std::string& path) {
  const auto first = path.find('/');
  if (first == std::string::npos) return "";
  if (path.compare(0, first, "engine") != 0) return path.substr(0, first);
  const auto second = path.find('/', first + 1);
  return second == std::string::npos ? "" : path.substr(0, second);
}

// One message per include that breaks the rules; empty when the tree is layered.
std::vector<std::string> layering_violations(const std::vector<Include>& includes) {
  const auto& ranks = engine_layer_ranks();
  std::vector<std::string> problems;
  for (const Include& inc : includes) {
    const std::string from = folder_of(inc.file);
    const std::string to = folder_of(inc.included);
    const std::string where = inc.file + ":" + std::to_string(inc.line) + ": includes " + inc.included;
    if (from == "firmware") {
      const auto& allowed = firmware_may_include();
      if (std::find(allowed.begin(), allowed.end(), to) == allowed.end()) {
        problems.push_back(where + ": the firmware includes only firmware/ and protocol/");
      }
      continue;
    }
    const auto from_rank = ranks.find(from);
    const auto to_rank = ranks.find(to);
    if (from_rank == ranks.end()) {
      problems.push_back(inc.file + ": folder " + from + " is not in the documented layer order");
    } else if (to_rank == ranks.end()) {
      problems.push_back(where + ": " + to + " is not a layer this file may include");
    } else if (from != to && to_rank->second >= from_rank->second) {
      problems.push_back(where + ": " + from + " (layer " + std::to_string(from_rank->second) + ") may not include " +
                         to + " (layer " + std::to_string(to_rank->second) + ")");
    }
  }
  return problems;
}

// Every quoted include of the project's own sources (system headers use <...>).
std::vector<Include> project_includes(const std::filesystem::path& root) {
  static const std::regex quoted_include(R"(^\s*#\s*include\s*"([^"]+)\")");
  std::vector<Include> includes;
  for (const char* top : {"engine", "firmware", "protocol", "python"}) {
    for (const auto& entry : std::filesystem::recursive_directory_iterator(root / top)) {
      const std::string ext = entry.path().extension().string();
      if (!entry.is_regular_file() || (ext != ".cpp" && ext != ".hpp" && ext != ".h" && ext != ".in")) continue;
      const std::string file = std::filesystem::relative(entry.path(), root).generic_string();
      std::ifstream in(entry.path());
      std::string text;
      for (int line = 1; std::getline(in, text); ++line) {
        std::smatch match;
        if (std::regex_search(text, match, quoted_include)) includes.push_back({file, line, match[1].str()});
      }
    }
  }
  std::sort(includes.begin(), includes.end(),
            [](const Include& a, const Include& b) { return a.file < b.file || (a.file == b.file && a.line < b.line); });
  return includes;
}

}  // namespace

TEST_CASE("layering: every include of engine/, firmware/, protocol/ and python/ goes down the documented order") {
  const std::vector<Include> includes = project_includes(HAPSCENE_SOURCE_DIR);
  REQUIRE(includes.size() > 100);  // the reader found the sources
  std::string report;
  for (const std::string& problem : layering_violations(includes)) report += problem + "\n";
  CHECK_MESSAGE(report.empty(), report);
}

TEST_CASE("layering: the check catches an upward include, a sideways one, a cycle and an unknown folder") {
  // Upward: the scene may not know the runner.
  CHECK(layering_violations({{"engine/scene/step.cpp", 3, "engine/run/runner.hpp"}}).size() == 1);
  // Sideways: devices and lua are on one level and do not know each other.
  CHECK(layering_violations({{"engine/devices/profile.cpp", 5, "engine/lua/script.hpp"}}).size() == 1);
  // The live view and the bench are on one level; the runner may not know the live view.
  CHECK(layering_violations({{"engine/serve/live_view.cpp", 5, "engine/bench/soak.hpp"}}).size() == 1);
  CHECK(layering_violations({{"engine/run/runner.cpp", 5, "engine/serve/live_view.hpp"}}).size() == 1);
  CHECK(layering_violations({{"engine/cli/run_session.hpp", 5, "engine/serve/live_view.hpp"},
                             {"engine/serve/live_view.cpp", 5, "engine/harness/validate.hpp"}})
            .empty());
  // A cycle between two folders always has one upward edge.
  CHECK(layering_violations({{"engine/effects/spring.hpp", 1, "engine/base/units.hpp"},
                             {"engine/base/units.hpp", 1, "engine/effects/spring.hpp"}})
            .size() == 1);
  // A folder nobody placed, and a firmware file that reaches into the host.
  CHECK(layering_violations({{"engine/gui/view.cpp", 1, "engine/base/errors.hpp"}}).size() == 1);
  CHECK(layering_violations({{"firmware/sampler.cpp", 7, "engine/devices/kinematics.hpp"}}).size() == 1);
  // The command line does not know the Python module above it; the module may use it.
  CHECK(layering_violations({{"engine/cli/run_command.cpp", 2, "python/scene.hpp"}}).size() == 1);
  CHECK(layering_violations({{"python/simulate.cpp", 2, "engine/cli/recorded_run.hpp"}}).empty());
  // Downward and within a folder (its subfolders included) is fine.
  CHECK(layering_violations({{"engine/cli/main.cpp", 1, "engine/base/errors.hpp"},
                             {"engine/devices/hil/wire.hpp", 1, "engine/devices/board_link.hpp"},
                             {"engine/devices/board_link.hpp", 1, "protocol/protocol.h"},
                             {"firmware/main.cpp", 1, "protocol/protocol.h"}})
            .empty());
}
