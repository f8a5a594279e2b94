#include "engine/load/validate_block.hpp"

#include "engine/base/physical_ranges.hpp"

namespace hapscene {
namespace {

// An optional whole number of ticks (or faults).
std::uint64_t count_or(ObjectReader& reader, std::string_view key, std::uint64_t fallback) {
  if (!reader.has(key)) {
    reader.get(key);
    return fallback;
  }
  return static_cast<std::uint64_t>(reader.integer(key, 0, 1'000'000'000));
}

// An optional fraction in [0, 1].
double fraction_or(ObjectReader& reader, std::string_view key, double fallback) {
  const double value = reader.quantity_or(key, Quantity::dimensionless, fallback, Bound::non_negative);
  if (value > 1.0) reader.fail(key, "must be a fraction in [0, 1], got " + format_number(value));
  return value;
}

// Ratios and lengths of the checks: finite, however lax.
constexpr Range kPositiveRatio{0.0, 1e6, true};
constexpr Range kPositiveLength_m{0.0, ranges::kLength_m.max, true};

}  // namespace

void parse_validate_block(ObjectReader& reader, ValidateThresholds* t) {
  // Checks.
  t->max_force_N = reader.quantity_or("max_force", Quantity::force_N, t->max_force_N, ranges::kPositiveForce_N);
  t->max_time_at_limit_fraction =
      fraction_or(reader, "max_time_at_limit", t->max_time_at_limit_fraction);
  t->max_slew_N_per_s = reader.quantity_or("max_slew", Quantity::force_rate_N_per_s,
                                           t->max_slew_N_per_s, ranges::kPositiveSlew_N_per_s);
  t->max_slip_ticks = count_or(reader, "max_slip_ticks", t->max_slip_ticks);
  t->max_passivity_ratio = reader.quantity_or("max_passivity_ratio", Quantity::dimensionless,
                                              t->max_passivity_ratio, kPositiveRatio);
  t->max_residual_amplitude_m = reader.quantity_or(
      "max_residual_amplitude", Quantity::length_m, t->max_residual_amplitude_m, kPositiveLength_m);
  t->max_amplitude_growth = reader.quantity_or("max_amplitude_growth", Quantity::dimensionless,
                                               t->max_amplitude_growth, kPositiveRatio);
  t->max_penetration_m = reader.quantity_or("max_penetration", Quantity::length_m,
                                            t->max_penetration_m, kPositiveLength_m);
  t->max_force_jitter_N = reader.quantity_or("max_force_jitter", Quantity::force_N,
                                             t->max_force_jitter_N, ranges::kPositiveForce_N);
  t->max_tick_compute_s = reader.quantity_or("max_tick_compute", Quantity::time_s,
                                             t->max_tick_compute_s, ranges::kPositiveDuration_s);
  t->max_script_faults = count_or(reader, "max_script_faults", t->max_script_faults);

  // Scenario construction.
  t->stiff_threshold_N_per_m = reader.quantity_or("stiff_threshold", Quantity::stiffness_N_per_m,
                                                  t->stiff_threshold_N_per_m, ranges::kPositiveStiffness_N_per_m);
  t->press_force_N =
      reader.quantity_or("press_force", Quantity::force_N, t->press_force_N, ranges::kPositiveForce_N);
  t->release_from_m =
      reader.quantity_or("release_from", Quantity::length_m, t->release_from_m, ranges::kPosition_m);
  reader.finish();
}

void parse_planar_validate_block(ObjectReader& reader, ValidateThresholds* t) {
  // The 1-DOF-only keys, refused with the reason before anything else is read.
  if (reader.has("max_slip_ticks")) {
    reader.fail("max_slip_ticks",
                "a 2-DOF scene has no slip check (planar profiles give no capstan slip force or step); "
                "this key is for 1-DOF scenes");
  }
  if (reader.has("stiff_threshold")) {
    reader.fail("stiff_threshold",
                "a 2-DOF scene's walls are its shapes (wall, box, circle, polygon), not regions found by "
                "a scan of the field; this key is for 1-DOF scenes");
  }
  // Checks, in the units of the 1-DOF block.
  t->max_force_N = reader.quantity_or("max_force", Quantity::force_N, t->max_force_N, ranges::kPositiveForce_N);
  t->max_time_at_limit_fraction =
      fraction_or(reader, "max_time_at_limit", t->max_time_at_limit_fraction);
  t->max_slew_N_per_s = reader.quantity_or("max_slew", Quantity::force_rate_N_per_s,
                                           t->max_slew_N_per_s, ranges::kPositiveSlew_N_per_s);
  t->max_passivity_ratio = reader.quantity_or("max_passivity_ratio", Quantity::dimensionless,
                                              t->max_passivity_ratio, kPositiveRatio);
  t->max_residual_amplitude_m = reader.quantity_or(
      "max_residual_amplitude", Quantity::length_m, t->max_residual_amplitude_m, kPositiveLength_m);
  t->max_amplitude_growth = reader.quantity_or("max_amplitude_growth", Quantity::dimensionless,
                                               t->max_amplitude_growth, kPositiveRatio);
  t->max_penetration_m = reader.quantity_or("max_penetration", Quantity::length_m,
                                            t->max_penetration_m, kPositiveLength_m);
  t->max_force_jitter_N = reader.quantity_or("max_force_jitter", Quantity::force_N,
                                             t->max_force_jitter_N, ranges::kPositiveForce_N);
  t->max_tick_compute_s = reader.quantity_or("max_tick_compute", Quantity::time_s,
                                             t->max_tick_compute_s, ranges::kPositiveDuration_s);
  t->max_script_faults = count_or(reader, "max_script_faults", t->max_script_faults);
  // 2-D only.
  t->max_pop_through = count_or(reader, "max_pop_through", t->max_pop_through);
  t->max_singularity_ticks = count_or(reader, "max_singularity_ticks", t->max_singularity_ticks);

  // Scenario construction.
  t->press_force_N =
      reader.quantity_or("press_force", Quantity::force_N, t->press_force_N, ranges::kPositiveForce_N);
  t->release_from_m = reader.quantity_or("release_from", Quantity::length_m, t->release_from_m, kPositiveLength_m);
  reader.finish();
}

}  // namespace hapscene
