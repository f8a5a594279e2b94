// `hapscene test [SPEC|FOLDER...]`: runs environment test specs (a folder: every
// *.test.json under it; default: every *.test.json under environments/ and scripts/, or
// when there are none, under the current folder).
// Prints PASS/FAIL per spec and each unmet expectation. Exit 0 when all pass, 1 when any fails, 2 when any spec (or its
// environment) is invalid input; the other specs still run. --json FILE and --junit FILE
// write every spec's verdict for tools and CI servers (engine/harness/test_report.hpp).
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/cli/arguments.hpp"
#include "engine/cli/commands.hpp"
#include "engine/cli/output_file.hpp"
#include "engine/cli/per_file.hpp"
#include "engine/cli/standard_output.hpp"
#include "engine/harness/test_report.hpp"
#include "engine/harness/test_spec.hpp"

namespace hapscene {

int test_command(std::vector<std::string> args) {
  Arguments arguments(std::move(args), "hapscene test");
  const bool verbose = arguments.take_flag("verbose");
  const std::optional<std::string> json_path = arguments.take_value("json");
  const std::optional<std::string> junit_path = arguments.take_value("junit");
  // Spec files as given; a folder stands for every *.test.json under it.
  std::vector<std::string> specs;
  for (const std::string& given : arguments.positionals()) {
    std::error_code error;
    if (!std::filesystem::is_directory(given, error)) {
      specs.push_back(given);
      continue;
    }
    const std::vector<std::string> found = find_test_specs({given});
    if (found.empty()) arguments.fail("no *.test.json under " + given);
    specs.insert(specs.end(), found.begin(), found.end());
  }
  // Without arguments: a repository's environments/ and scripts/, or else (a folder of
  // one's own specs) every spec under the current folder.
  if (arguments.positionals().empty()) {
    specs = find_test_specs({"environments", "scripts"});
    if (specs.empty()) specs = find_test_specs({"."});
    if (specs.empty()) arguments.fail("no *.test.json under environments/, scripts/ or the current folder");
  }

  // The reports' files are checked before any spec runs.
  std::vector<std::pair<std::string, std::string>> outputs;
  if (json_path) outputs.emplace_back("json", *json_path);
  if (junit_path) outputs.emplace_back("junit", *junit_path);
  if (const std::string problem = output_path_problem(outputs, specs); !problem.empty()) arguments.fail(problem);

  // Each spec its own verdict: one that cannot be loaded (the spec or its environment)
  // prints its error and a FAIL line, and the others still run (engine/cli/per_file.hpp).
  int exit_code = kExitOk;
  int failed = 0;
  std::size_t expectations = 0;
  std::vector<SpecRecord> records;
  for (const std::string& spec : specs) {
    SpecRecord record;
    record.spec_path = printable(spec);
    const auto start = std::chrono::steady_clock::now();
    const int spec_code = run_for_file(
        [&] {
          SpecResult r = run_test_spec(spec);
          // Paths, pointers and messages carry text from files and scripts: printable.
          print_out("%s %s (%zu expectations)\n", r.pass ? "PASS" : "FAIL", printable(r.spec_path).c_str(),
                    r.outcomes.size());
          expectations += r.outcomes.size();
          for (const SpecOutcome& o : r.outcomes) {
            if (!o.pass || verbose) {
              print_out("  %s %s: %s\n", o.pass ? "ok  " : "FAIL", printable(o.what).c_str(), printable(o.message).c_str());
            }
          }
          record.environment_path = printable(r.environment_path);
          record.outcomes = std::move(r.outcomes);
          return r.pass ? kExitOk : kExitFailure;
        },
        &record.error);
    record.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    record.verdict = spec_code == kExitOk ? SpecVerdict::pass
                     : spec_code == kExitInvalidInput ? SpecVerdict::invalid
                                                      : SpecVerdict::fail;
    if (spec_code == kExitInvalidInput) print_out("FAIL %s: invalid input (see the error above)\n", printable(spec).c_str());
    failed += spec_code == kExitOk ? 0 : 1;
    exit_code = worst_exit_code(exit_code, spec_code);
    records.push_back(std::move(record));
  }
  print_out("%zu specs, %zu expectations: %s\n", specs.size(), expectations,
            failed == 0 ? "all pass" : (std::to_string(failed) + " specs failed").c_str());
  // A report that cannot be written fails the command (exit 1) and says which.
  const int written = run_for_file([&] {
    if (json_path) write_output_file(*json_path, test_results_json(records).dump(2) + "\n");
    if (junit_path) write_output_file(*junit_path, test_results_junit(records));
    return kExitOk;
  });
  return worst_exit_code(exit_code, written);
}

}  // namespace hapscene
