// The 1-D and the 2-D harness share one implementation of what they do alike (the report's
// rows and --quiet line, the checks both judge, the force trace, the open loop, the keys of
// a spec's scenario expectation): the same inputs give the same text in both dimensions,
// so a fix to one reaches the other.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/base/errors.hpp"
#include "engine/base/object_reader.hpp"
#include "engine/harness/check_parts.hpp"
#include "engine/harness/metrics_parts.hpp"
#include "engine/harness/open_loop.hpp"
#include "engine/harness/planar_checks.hpp"
#include "engine/harness/planar_report.hpp"
#include "engine/harness/report.hpp"
#include "engine/harness/spec_judging.hpp"
#include "engine/harness/test_spec_parts.hpp"
#include "tests/support.hpp"

using namespace hapscene;

namespace {

const std::vector<CheckResult> kChecks = {
    {"max_force", 1.0, 2.0, "N", true, "at the wall"},
    {"passivity", 3.0, 1.0, "", false, "created 3 mJ"},
};

template <typename Report>
void fill(Report* report) {
  report->scene_name = "twin";
  report->source_path = "twin.json";
  report->scenarios.resize(2);
  report->scenarios[0].scenario.name = "press";
  report->scenarios[0].scenario.description = "the hand presses";
  report->scenarios[0].checks = kChecks;
  report->scenarios[0].pass = false;
  report->scenarios[1].scenario.name = "hold";
  report->scenarios[1].scenario.description = "nothing to hold";
  report->scenarios[1].scenario.applicable = false;
  report->pass = false;
}

// The table below its header.
std::string rows(const std::string& table) { return table.substr(report_table_header(table).size()); }

}  // namespace

TEST_CASE("dimension parts: the 1-D and 2-D reports write the same rows, summary and --quiet line") {
  ValidationReport one;
  PlanarValidationReport two;
  fill(&one);
  fill(&two);
  CHECK(format_report_line(one) == "FAIL twin (twin.json): 1 of 2 checks failed: press/passivity\n");
  CHECK(format_report_line(two) == format_report_line(one));
  CHECK(rows(format_report_table(two)) == rows(format_report_table(one)));
  CHECK(rows(format_report_table(one)).ends_with("\nresult: FAIL (1 of 2 checks failed: press/passivity)\n"));
  CHECK(rows(format_report_summary(two)) == rows(format_report_summary(one)));
  // The JSON both write alike: the frame, the options and a scenario's entry.
  const nlohmann::json a = report_to_json(one);
  const nlohmann::json b = report_to_json(two);
  CHECK(a["schema"] == b["schema"]);
  CHECK(a["scene_checks"] == b["scene_checks"]);
  CHECK(a["scenarios"][0]["checks"] == b["scenarios"][0]["checks"]);
  // A scenario that does not apply has every key: no metrics (it did not run), no checks.
  CHECK(a["scenarios"][1] == nlohmann::json{{"name", "hold"}, {"description", "nothing to hold"},
                                            {"applicable", false}, {"duration_s", 0.0}, {"pass", true},
                                            {"metrics", nullptr}, {"checks", nlohmann::json::array()}});
  CHECK(b["scenarios"][1]["start_m"] == nlohmann::json::array({0.0, 0.0}));
}

TEST_CASE("dimension parts: the shared checks and the force trace read the same in 1-D and 2-D") {
  CHECK(where_when(0.012, 0.5) == "at 12.00 mm, t 0.500 s");
  CHECK(where_when(Vec2{{0.012, 0.13}}, 0.5) == "at (12.00, 130.00) mm, t 0.500 s");

  // A force along x in 2-D measures as the same force in 1-D.
  std::vector<TickRecord> line(5);
  std::vector<PlanarValidateRecord> plane(5);
  const double output_N[] = {0.0, 1.0, 3.0, 3.0, -2.0};
  for (std::size_t k = 0; k < 5; ++k) {
    line[k].t_s = plane[k].t_s = 0.001 * static_cast<double>(k);
    line[k].x_true_m = plane[k].x_true_m[0] = 0.01 * static_cast<double>(k);
    line[k].output_N = line[k].requested_N = plane[k].output_N[0] = plane[k].requested_N[0] = output_N[k];
  }
  ScenarioMetrics m1;
  PlanarScenarioMetrics m2;
  measure_force_trace(line, 3.0, 0.001, &m1);
  measure_force_trace(plane, 3.0, 0.001, &m2);
  CHECK(m1.max_output_N == 3.0);
  CHECK(m1.max_output_x_m == 0.02);
  CHECK(m1.max_slew_N_per_s == doctest::Approx(5000.0));
  CHECK(m1.time_at_limit_fraction == doctest::Approx(0.4));
  CHECK(m2.max_output_N == m1.max_output_N);
  CHECK(m2.max_output_x_m[0] == m1.max_output_x_m);
  CHECK(m2.max_slew_N_per_s == m1.max_slew_N_per_s);
  CHECK(m2.force_jitter_N == m1.force_jitter_N);
  CHECK(m2.jitter_peak_N == m1.jitter_peak_N);
  CHECK(m2.jitter_peak_t_s == m1.jitter_peak_t_s);
  CHECK(m2.time_at_limit_s == m1.time_at_limit_s);
}

TEST_CASE("dimension parts: the open loop's points are described and ordered per dimension") {
  CHECK(describe_point(0.012, 0.0, 0.0) == "x 12.00 mm, v 0 m/s, t 0 s");
  CHECK(describe_point(Vec2{{0.012, 0.13}}, Vec2{}, 0.0) == "x 12.00 mm, y 130.00 mm, v (0, 0) m/s, t 0 s");
  // 1-D keeps the lowest position that met a fault, 2-D the first point in the order given.
  CHECK(point_order_key(0.012, 7) == 0.012);
  CHECK(point_order_key(Vec2{{0.012, 0.13}}, 7) == 7.0);
  CHECK(motion_scan_velocities<1>().size() == std::size(kMotionScanVelocities_m_per_s));
  CHECK(motion_scan_velocities<2>().size() == 1 + 4 * 4);  // rest, then four speeds along +x, -x, +y, -y
}

TEST_CASE("dimension parts: a scenario expectation's keys are read alike, with each dimension's check names") {
  const auto parse = [](const std::string& text, bool planar) {
    const nlohmann::json value = nlohmann::json::parse(text);
    ObjectReader r(value, "/scenarios/0", "spec.test.json");
    ScenarioExpectation e;
    if (planar) parse_scenario_expectation_keys(r, kPlanarCheckNames, "2-D check", &e);
    else parse_scenario_expectation_keys(r, kCheckNames, "check", &e);
    r.finish();
    return e;
  };
  const ScenarioExpectation e =
      parse(R"({"min_half_cycles": 2, "frequency": ["1 Hz", "3 Hz"], "pass": false, "fail": ["passivity"]})", true);
  CHECK(e.min_half_cycles == 2);
  CHECK(e.frequency_Hz->second == 3.0);
  CHECK(e.pass == false);
  CHECK(e.fail == std::vector<std::string>{"passivity"});
  CHECK(test::input_error_of([&] { parse(R"({"fail": ["slip"]})", true); }) ==
        "spec.test.json: /scenarios/0/fail/0: unknown 2-D check \"slip\" (did you mean \"slew\"?)");
  CHECK(test::input_error_of([&] { parse(R"({"fail": ["pop_through"]})", false); }) ==
        "spec.test.json: /scenarios/0/fail/0: unknown check \"pop_through\"");
}
