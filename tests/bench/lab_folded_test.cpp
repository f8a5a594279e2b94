// The hand-folded floor computes what the sketch computes: the same duty and direction
// every tick on recorded readings, for each lab environment (only the rounding of the
// folded constants differs).
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "engine/bench/lab_baseline.hpp"
#include "engine/bench/tick_bench.hpp"
#include "engine/load/environment.hpp"

using namespace hapscene;

TEST_CASE("lab baseline: the folded floor gives the sketch's duty and direction") {
  for (const char* name : {"spring", "wall", "damper", "texture"}) {
    CAPTURE(name);
    const Scene scene = load_environment_file(std::string(HAPSCENE_SOURCE_DIR) + "/environments/" + name + ".json");
    LabBaselineKind kind{};
    LabBaselineConstants constants;
    REQUIRE(lab_baseline_for(scene, &kind, &constants));
    const LabFoldedConstants folded = fold_lab_constants(constants);
    const auto sketch = kind == LabBaselineKind::spring ? lab_spring_tick
                        : kind == LabBaselineKind::wall ? lab_wall_tick
                        : kind == LabBaselineKind::damper ? lab_damper_tick : lab_texture_tick;
    const auto floor = kind == LabBaselineKind::spring ? lab_spring_folded
                       : kind == LabBaselineKind::wall ? lab_wall_folded
                       : kind == LabBaselineKind::damper ? lab_damper_folded : lab_texture_folded;
    LabBaselineState a, b;
    int differing = 0, pushing = 0;
    for (const std::int32_t raw : record_sensor_counts(scene, 2.0)) {
      sketch(constants, raw, &a);
      floor(folded, raw, &b);
      if (std::abs(a.duty - b.duty) > 1e-9 || (a.duty > 1e-9 && a.direction_high != b.direction_high)) ++differing;
      if (a.duty > 0.01) ++pushing;
    }
    // A texture's field edge may fall either way of a rounding: a tick or two, no more.
    CHECK(differing <= 2);
    CHECK(pushing > 100);  // the recording exercises the force law
  }
}
