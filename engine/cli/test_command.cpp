// `hapscene test [SPEC|FOLDER...]`: runs environment test specs (a folder: every
// *.test.json under it; default: every *.test.json under environments/ and scripts/, or
// when there are none, under the current folder).
// Prints PASS/FAIL per spec and each unmet expectation. Exit 0 when all pass, 1 when any fails, 2 when any spec (or its
// environment) is invalid input; the other specs still run.
#include <cstdio>
#include <filesystem>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/cli/arguments.hpp"
#include "engine/cli/commands.hpp"
#include "engine/cli/per_file.hpp"
#include "engine/cli/standard_output.hpp"
#include "engine/harness/test_spec.hpp"

namespace hapscene {

int test_command(std::vector<std::string> args) {
  Arguments arguments(std::move(args), "hapscene test");
  const bool verbose = arguments.take_flag("verbose");
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

  // Each spec its own verdict: one that cannot be loaded (the spec or its environment)
  // prints its error and a FAIL line, and the others still run (engine/cli/per_file.hpp).
  int exit_code = kExitOk;
  int failed = 0;
  std::size_t expectations = 0;
  for (const std::string& spec : specs) {
    const int spec_code = run_for_file([&] {
      const SpecResult r = run_test_spec(spec);
      // Paths, pointers and messages carry text from files and scripts: printable.
      print_out("%s %s (%zu expectations)\n", r.pass ? "PASS" : "FAIL", printable(r.spec_path).c_str(),
                r.outcomes.size());
      expectations += r.outcomes.size();
      for (const SpecOutcome& o : r.outcomes) {
        if (!o.pass || verbose) {
          print_out("  %s %s: %s\n", o.pass ? "ok  " : "FAIL", printable(o.what).c_str(), printable(o.message).c_str());
        }
      }
      return r.pass ? kExitOk : kExitFailure;
    });
    if (spec_code == kExitInvalidInput) print_out("FAIL %s: invalid input (see the error above)\n", printable(spec).c_str());
    failed += spec_code == kExitOk ? 0 : 1;
    exit_code = worst_exit_code(exit_code, spec_code);
  }
  print_out("%zu specs, %zu expectations: %s\n", specs.size(), expectations,
            failed == 0 ? "all pass" : (std::to_string(failed) + " specs failed").c_str());
  return exit_code;
}

}  // namespace hapscene
