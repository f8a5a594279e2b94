#include "engine/harness/test_report.hpp"

#include "engine/base/format.hpp"

namespace hapscene {



const char* spec_verdict_name(SpecVerdict verdict) {
  switch (verdict) {
    case SpecVerdict::pass: return "pass";
    case SpecVerdict::fail: return "fail";
    case SpecVerdict::invalid: return "invalid";
  }
  return "fail";
}

nlohmann::json test_results_json(const std::vector<SpecRecord>& records) {
  nlohmann::json specs = nlohmann::json::array();
  std::size_t passed = 0, failed = 0, invalid = 0, expectations = 0;
  for (const SpecRecord& r : records) {
    nlohmann::json outcomes = nlohmann::json::array();
    for (const SpecOutcome& o : r.outcomes) {
      outcomes.push_back({{"what", printable(o.what)}, {"pass", o.pass}, {"message", printable(o.message)}});
    }
    nlohmann::json spec{{"spec", r.spec_path},
              {"environment", r.environment_path.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.environment_path)},
              {"verdict", spec_verdict_name(r.verdict)},
              {"error", r.error.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.error)},
              {"seconds", r.seconds},
              {"expectations", outcomes}};
    specs.push_back(std::move(spec));
    passed += r.verdict == SpecVerdict::pass ? 1 : 0;
    failed += r.verdict == SpecVerdict::fail ? 1 : 0;
    invalid += r.verdict == SpecVerdict::invalid ? 1 : 0;
    expectations += r.outcomes.size();
  }
  return {{"format", "hapscene-test/1"},
          {"summary",
           {{"specs", records.size()},
            {"passed", passed},
            {"failed", failed},
            {"invalid", invalid},
            {"expectations", expectations}}},
          {"specs", specs}};
}

std::string xml_escaped(std::string_view text) {
  const std::string safe = printable(text);
  std::string out;
  out.reserve(safe.size());
  for (std::size_t i = 0; i < safe.size(); ++i) {
    const char c = safe[i];
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default:
        // U+FFFE and U+FFFF (EF BF BE, EF BF BF) are valid UTF-8 but not XML characters.
        if (static_cast<unsigned char>(c) == 0xef && i + 2 < safe.size() &&
            static_cast<unsigned char>(safe[i + 1]) == 0xbf &&
            (static_cast<unsigned char>(safe[i + 2]) == 0xbe || static_cast<unsigned char>(safe[i + 2]) == 0xbf)) {
          out += static_cast<unsigned char>(safe[i + 2]) == 0xbe ? "\\xef\\xbf\\xbe" : "\\xef\\xbf\\xbf";
          i += 2;
        } else {
          out += c;
        }
    }
  }
  return out;
}

std::string test_results_junit(const std::vector<SpecRecord>& records) {
  std::size_t cases = 0, failures = 0, errors = 0;
  double total_s = 0.0;
  std::string suites;
  for (const SpecRecord& r : records) {
    const std::string name = xml_escaped(r.spec_path);
    total_s += r.seconds;
    std::size_t suite_failures = 0;
    std::string body;
    for (const SpecOutcome& o : r.outcomes) {
      body += "    <testcase classname=\"" + name + "\" name=\"" + xml_escaped(o.what) + "\"";
      if (o.pass) {
        body += "/>\n";
        continue;
      }
      ++suite_failures;
      const std::string message = xml_escaped(o.message);
      body += ">\n      <failure message=\"" + message + "\">" + message + "</failure>\n    </testcase>\n";
    }
    // A spec that did not load, or a run that failed before its expectations were judged.
    const bool error_case = !r.error.empty();
    if (error_case) {
      const std::string message = xml_escaped(r.error);
      const char* element = r.verdict == SpecVerdict::invalid ? "error" : "failure";
      body += "    <testcase classname=\"" + name + "\" name=\"" +
              (r.verdict == SpecVerdict::invalid ? std::string("load") : std::string("run")) + "\">\n      <" + element +
              " message=\"" + message + "\">" + message + "</" + element + ">\n    </testcase>\n";
    }
    const std::size_t suite_cases = r.outcomes.size() + (error_case ? 1 : 0);
    const std::size_t suite_errors = error_case && r.verdict == SpecVerdict::invalid ? 1 : 0;
    if (error_case && suite_errors == 0) ++suite_failures;
    cases += suite_cases;
    failures += suite_failures;
    errors += suite_errors;
    suites += "  <testsuite name=\"" + name + "\" tests=\"" + std::to_string(suite_cases) + "\" failures=\"" +
              std::to_string(suite_failures) + "\" errors=\"" + std::to_string(suite_errors) + "\" time=\"" +
              printf_string("%.3f", r.seconds) + "\">\n" + body + "  </testsuite>\n";
  }
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"hapscene test\" tests=\"" +
         std::to_string(cases) + "\" failures=\"" + std::to_string(failures) + "\" errors=\"" + std::to_string(errors) +
         "\" time=\"" + printf_string("%.3f", total_s) + "\">\n" + suites + "</testsuites>\n";
}

}  // namespace hapscene
