// The test command's reports (engine/harness/test_report.hpp): what a CI server reads of a
// class's or a repository's specs. The JSON is checked against its schema and the XML read
// by a real parser in the json_schemas test; here, the counts, the escaping and the command.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "engine/harness/test_report.hpp"
#include "tests/cli/cli_support.hpp"
#include "tests/scratch_folder.hpp"

namespace hapscene::HAPSCENE_TEST_FILE {
namespace {

std::vector<SpecRecord> three_records() {
  SpecRecord pass{"a.test.json", "a.json", SpecVerdict::pass, "", 0.25, {{"/forces/0", true, "ok"}}};
  SpecRecord fail{"b.test.json", "b.json", SpecVerdict::fail, "", 0.5,
                  {{"/forces/0", true, "ok"}, {"/never_exceeds", false, "largest 7 N > 5 N & <rising>"}}};
  SpecRecord invalid{"c.test.json", "", SpecVerdict::invalid, "c.test.json:1:2: bad \"key\"", 0.0, {}};
  return {pass, fail, invalid};
}

TEST_CASE("test report: JUnit counts a failure per unmet expectation and an error per spec that did not load") {
  const std::string xml = test_results_junit(three_records());
  CHECK(xml.starts_with("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"hapscene test\" tests=\"4\" "
                        "failures=\"1\" errors=\"1\" time=\"0.750\">\n"));
  CHECK(xml.find("<testsuite name=\"a.test.json\" tests=\"1\" failures=\"0\" errors=\"0\" time=\"0.250\">") !=
        std::string::npos);
  CHECK(xml.find("<testsuite name=\"b.test.json\" tests=\"2\" failures=\"1\" errors=\"0\"") != std::string::npos);
  CHECK(xml.find("<failure message=\"largest 7 N &gt; 5 N &amp; &lt;rising&gt;\">largest 7 N &gt; 5 N &amp; "
                 "&lt;rising&gt;</failure>") != std::string::npos);
  CHECK(xml.find("<testcase classname=\"c.test.json\" name=\"load\">\n      <error message=\"c.test.json:1:2: bad "
                 "&quot;key&quot;\">") != std::string::npos);
  CHECK(xml.ends_with("</testsuites>\n"));
}

TEST_CASE("test report: the JSON has a summary and every spec in order, null where nothing is known") {
  const nlohmann::json results = test_results_json(three_records());
  CHECK(results["format"] == "hapscene-test/1");
  CHECK(results["summary"] == nlohmann::json{{"specs", 3}, {"passed", 1}, {"failed", 1}, {"invalid", 1},
                                             {"expectations", 3}});
  REQUIRE(results["specs"].size() == 3);
  CHECK(results["specs"][1]["verdict"] == "fail");
  CHECK(results["specs"][1]["expectations"][1]["pass"] == false);
  CHECK(results["specs"][2]["environment"].is_null());
  CHECK(results["specs"][2]["error"] == "c.test.json:1:2: bad \"key\"");
  CHECK(results["specs"][0]["error"].is_null());
}

TEST_CASE("test report: text from files cannot break the XML (control characters, quotes, non-characters)") {
  CHECK(xml_escaped("a<b>&\"c'") == "a&lt;b&gt;&amp;&quot;c&apos;");
  CHECK(xml_escaped("line\nnext\x1b[31m") == "line\\nnext\\x1b[31m");
  CHECK(xml_escaped("\xef\xbf\xbe|\xef\xbf\xbf|\xef\xbf\xbd") == "\\xef\\xbf\\xbe|\\xef\\xbf\\xbf|\xef\xbf\xbd");
  CHECK(xml_escaped("\xff") == "\\xff");  // not UTF-8
}

TEST_CASE("test report: hapscene test --json and --junit write after every spec ran, and refuse an input as output") {
  const test::ScratchFolder folder("test_report_cli");
  const std::string json_path = (folder.dir / "results.json").string();
  const std::string xml_path = (folder.dir / "results.xml").string();
  const test::CliOutcome ran = test::run_cli("test environments/spring.test.json environments/wall.test.json --json " +
                                             json_path + " --junit " + xml_path);
  CHECK(ran.exit_code == 0);
  const nlohmann::json results = nlohmann::json::parse(test::slurp_file(json_path));
  CHECK(results["summary"]["passed"] == 2);
  CHECK(results["specs"][0]["spec"] == "environments/spring.test.json");
  CHECK(results["specs"][1]["environment"] == "environments/wall.json");
  CHECK(test::slurp_file(xml_path).find("<testsuite name=\"environments/wall.test.json\"") != std::string::npos);

  const test::CliOutcome onto_spec = test::run_cli("test environments/spring.test.json --junit environments/spring.test.json");
  CHECK(onto_spec.exit_code == 2);
  CHECK(onto_spec.err.find("--junit environments/spring.test.json: is an input file of this command") !=
        std::string::npos);
  const test::CliOutcome both = test::run_cli("test environments/spring.test.json --json " + json_path + " --junit " +
                                              json_path);
  CHECK(both.exit_code == 2);
  CHECK(both.err.find("is also given to --json") != std::string::npos);
  // A report that cannot be written: the verdicts are printed, the exit status is 1.
  const test::CliOutcome full = test::run_cli("test environments/spring.test.json --json /dev/full");
  CHECK(full.exit_code == 1);
  CHECK(full.out.find("PASS environments/spring.test.json") != std::string::npos);
  CHECK(full.err.find("/dev/full: write failed") != std::string::npos);
}

TEST_CASE("test jobs: specs run in processes of their own print the same bytes as one after another") {
  const test::ScratchFolder folder("test_jobs_same");
  folder.write("broken.test.json", "{\"environment\": ");
  const std::string specs = "environments/spring.test.json environments/planar/haplink_box_inside.test.json " +
                            (folder.dir / "broken.test.json").string() + " environments/wall.test.json";
  const test::CliOutcome serial = test::run_cli("test " + specs);
  const test::CliOutcome parallel = test::run_cli("test " + specs + " --jobs 3");
  CHECK(serial.exit_code == 2);
  CHECK(parallel.exit_code == 2);
  CHECK(parallel.out == serial.out);
  CHECK(parallel.err == serial.err);
  CHECK(serial.out.find("FAIL " + (folder.dir / "broken.test.json").string() + ": invalid input (see the error above)") !=
        std::string::npos);
}

TEST_CASE("test jobs: a spec past --spec-timeout is stopped and failed, and the others still get their verdicts") {
  const test::ScratchFolder folder("test_jobs_timeout");
  // Forces only: milliseconds. The maze's spec runs validate's scenarios: 2.7 s here (Release),
  // 30 s under AddressSanitizer; stopped at 0.3 s.
  const std::string quick = folder.write(
      "quick.test.json", std::string(R"({"environment": ")") + HAPSCENE_SOURCE_DIR +
                             R"(/environments/spring.json", "forces": [{"x": "10 mm", "force": "-1 N"}]})");
  const std::string json_path = (folder.dir / "results.json").string();
  const test::CliOutcome outcome = test::run_cli("test environments/planar/haplink_maze.test.json " + quick +
                                                 " --spec-timeout 0.3s --json " + json_path);
  CHECK(outcome.exit_code == 1);
  CHECK(outcome.out.find("FAIL environments/planar/haplink_maze.test.json: no verdict (see the error above)\n") !=
        std::string::npos);
  CHECK(outcome.err.find("hapscene: environments/planar/haplink_maze.test.json: ran longer than --spec-timeout 0.3 s: "
                         "stopped\n") != std::string::npos);
  CHECK(outcome.out.find("PASS " + quick + " (1 expectations)") != std::string::npos);
  const nlohmann::json results = nlohmann::json::parse(test::slurp_file(json_path));
  CHECK(results["specs"][0]["verdict"] == "fail");
  CHECK(results["specs"][1]["verdict"] == "pass");
}

}  // namespace
}  // namespace hapscene::HAPSCENE_TEST_FILE
