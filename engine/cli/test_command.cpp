// `hapscene test [SPEC|FOLDER...]`: runs environment test specs (a folder: every
// *.test.json under it; default: every *.test.json under environments/ and scripts/, or
// when there are none, under the current folder).
// Prints PASS/FAIL per spec and each unmet expectation. Exit 0 when all pass, 1 when any fails, 2 when any spec (or its
// environment) is invalid input; the other specs still run. --json FILE and --junit FILE
// write every spec's verdict for tools and CI servers (engine/harness/test_report.hpp);
// --jobs runs several at once, each in a process of its own (engine/cli/spec_runs.hpp).
#include <algorithm>
#include <cstdio>
#include <thread>
#include <filesystem>
#include <optional>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/cli/arguments.hpp"
#include "engine/cli/commands.hpp"
#include "engine/cli/output_file.hpp"
#include "engine/cli/option_definitions.hpp"
#include "engine/cli/per_file.hpp"
#include "engine/cli/spec_runs.hpp"
#include "engine/cli/standard_output.hpp"
#include "engine/harness/test_report.hpp"
#include "engine/harness/test_spec.hpp"

namespace hapscene {

int test_command(std::vector<std::string> args) {
  Arguments arguments(std::move(args), "hapscene test");
  const bool verbose = arguments.take_flag("verbose");
  const std::optional<std::string> json_path = arguments.take_value("json");
  const std::optional<std::string> junit_path = arguments.take_value("junit");
  // --jobs N: N specs at once, each in a process of its own (0: one per core); --spec-timeout.
  const auto jobs_given = arguments.take(option::test_jobs);
  const std::optional<double> timeout_s = arguments.take(option::test_spec_timeout);
  const int jobs = !jobs_given ? 1
                   : *jobs_given == 0 ? static_cast<int>(std::max(1u, std::thread::hardware_concurrency()))
                                      : static_cast<int>(*jobs_given);
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
  // Printed in the specs' order however they ran (engine/cli/spec_runs.hpp).
  int exit_code = kExitOk;
  int failed = 0;
  std::size_t expectations = 0;
  std::vector<SpecRecord> records;
  const auto report = [&](SpecRun& run) {
    const SpecRecord& r = run.record;
    if (!run.stderr_text.empty()) {
      flush_out();
      std::fputs(run.stderr_text.c_str(), stderr);
    }
    if (r.error.empty()) {
      print_out("%s %s (%zu expectations)\n", r.verdict == SpecVerdict::pass ? "PASS" : "FAIL", r.spec_path.c_str(),
                r.outcomes.size());
      for (const SpecOutcome& o : r.outcomes) {
        if (!o.pass || verbose) print_out("  %s %s: %s\n", o.pass ? "ok  " : "FAIL", o.what.c_str(), o.message.c_str());
      }
    } else {
      print_out("FAIL %s: %s (see the error above)\n", r.spec_path.c_str(),
                r.verdict == SpecVerdict::invalid ? "invalid input" : "no verdict");
    }
    expectations += r.outcomes.size();
    failed += run.exit_code == kExitOk ? 0 : 1;
    exit_code = worst_exit_code(exit_code, run.exit_code);
    records.push_back(std::move(run.record));
  };
  if (jobs == 1 && !timeout_s) {
    for (const std::string& spec : specs) {
      SpecRun run = run_spec_here(spec);
      report(run);
    }
  } else {
    run_specs_in_processes(specs, jobs, timeout_s.value_or(0.0), [&](std::size_t, SpecRun& run) { report(run); });
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
