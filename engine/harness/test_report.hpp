#pragma once
// What `hapscene test --json FILE` and `--junit FILE` write: every spec's verdict with its
// expectations, in the order run. The JSON ("hapscene-test/1",
// schemas/test-results.schema.json) is for tools; the JUnit XML is the form CI servers
// show as test results (GitLab, Jenkins, GitHub's test reporters): a <testsuite> per spec,
// a <testcase> per expectation, a spec that did not load one <testcase> with an <error>.
// docs/reference/test-specs.md gives both formats.
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/harness/test_spec.hpp"

namespace hapscene {

enum class SpecVerdict {
  pass,     // every expectation met
  fail,     // an expectation unmet, or the run failed (`error` says how)
  invalid,  // the spec or its environment is invalid input (exit 2; `error` says where)
};

// One spec as `hapscene test` ran it. Paths and texts are printable.
struct SpecRecord {
  std::string spec_path;
  std::string environment_path;  // "" when the spec did not load
  SpecVerdict verdict{SpecVerdict::pass};
  std::string error;             // the error printed for it, when there was one
  double seconds{};              // wall time the spec took
  std::vector<SpecOutcome> outcomes;
};

// "pass", "fail", "invalid".
const char* spec_verdict_name(SpecVerdict verdict);

nlohmann::json test_results_json(const std::vector<SpecRecord>& records);
std::string test_results_junit(const std::vector<SpecRecord>& records);

// Text made safe for XML character data and attribute values: printable() (no control
// characters, valid UTF-8), then & < > " ' as entities and the two non-characters
// U+FFFE and U+FFFF as escapes.
std::string xml_escaped(std::string_view text);

}  // namespace hapscene
