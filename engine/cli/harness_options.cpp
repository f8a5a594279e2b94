#include "engine/cli/harness_options.hpp"

#include <algorithm>
#include <string>

#include "engine/base/units.hpp"
#include "engine/cli/option_definitions.hpp"

namespace hapscene {

HarnessOptions take_harness_options(Arguments& arguments) {
  HarnessOptions o;
  o.hand_stiffness_N_per_m = arguments.take(option::hand_stiffness).value_or(o.hand_stiffness_N_per_m);
  o.hand_damping_N_s_per_m = arguments.take(option::hand_damping).value_or(o.hand_damping_N_s_per_m);
  o.hand_mass_kg = arguments.take(option::hand_mass).value_or(o.hand_mass_kg);
  o.noise_counts = arguments.take(option::noise).value_or(-1.0);
  o.seed = arguments.take(option::seed).value_or(o.seed);
  o.free_start_m = arguments.take(option::free_start).value_or(o.free_start_m);
  return o;
}

void parse_free_start(const Arguments& arguments, const std::string& text, double* x_m) {
  *x_m = parse_option_quantity(text, option::free_start, arguments.command() + ": --start");
}

void parse_free_start(const Arguments& arguments, const std::string& text, Vec2* x_m) {
  *x_m = parse_planar_point(arguments, "start", text, option::run_start);
}

Vec2 parse_planar_point(const Arguments& arguments, const std::string& name, const std::string& text,
                        const QuantityOption& option) {
  const std::size_t comma = text.find(',');
  if (comma == std::string::npos || text.find(',', comma + 1) != std::string::npos) {
    arguments.fail("--" + name + ": a 2-DOF environment takes X,Y, got \"" + text + "\"");
  }
  const std::string what = arguments.command() + ": --" + name;
  return Vec2{{parse_option_quantity(text.substr(0, comma), option, what + " X"),
               parse_option_quantity(text.substr(comma + 1), option, what + " Y")}};
}

}  // namespace hapscene
