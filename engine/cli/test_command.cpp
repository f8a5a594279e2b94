// `hapscene test [SPEC...]`: runs environment test specs (default: every *.test.json
// under environments/ and scripts/). Prints PASS/FAIL per spec and each unmet
// expectation. Exit 0 when all pass, 1 when any fails, 2 for an invalid spec.
#include <cstdio>

#include "engine/base/errors.hpp"
#include "engine/cli/arguments.hpp"
#include "engine/cli/commands.hpp"
#include "engine/harness/test_spec.hpp"

namespace hapscene {

int test_command(std::vector<std::string> args) {
  Arguments arguments(std::move(args), "hapscene test");
  const bool verbose = arguments.take_flag("verbose");
  std::vector<std::string> specs = arguments.positionals();
  if (specs.empty()) {
    specs = find_test_specs({"environments", "scripts"});
    if (specs.empty()) arguments.fail("no *.test.json under environments/ or scripts/");
  }

  // Check every spec can be read before reporting: an invalid one is exit code 2.
  std::vector<SpecResult> results;
  for (const std::string& spec : specs) results.push_back(run_test_spec(spec));

  int failed = 0;
  std::size_t expectations = 0;
  for (const SpecResult& r : results) {
    std::printf("%s %s (%zu expectations)\n", r.pass ? "PASS" : "FAIL", r.spec_path.c_str(), r.outcomes.size());
    expectations += r.outcomes.size();
    for (const SpecOutcome& o : r.outcomes) {
      if (!o.pass || verbose) std::printf("  %s %s: %s\n", o.pass ? "ok  " : "FAIL", o.what.c_str(), o.message.c_str());
    }
    failed += r.pass ? 0 : 1;
  }
  std::printf("%zu specs, %zu expectations: %s\n", results.size(), expectations,
              failed == 0 ? "all pass" : (std::to_string(failed) + " specs failed").c_str());
  return failed == 0 ? kExitOk : kExitFailure;
}

}  // namespace hapscene
