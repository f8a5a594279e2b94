#pragma once
// What the 1-D and the 2-D test specs (test_spec.cpp, planar_test_spec.cpp) read alike:
// the environment a spec names, quantities checked against the command line's ranges,
// optional booleans, the virtual hand's options. Internal to the harness.
#include <optional>
#include <string>
#include <string_view>

#include "engine/base/object_reader.hpp"
#include "engine/harness/option_ranges.hpp"
#include "engine/harness/scenario.hpp"

namespace hapscene {

// The environment of the spec at `spec_path`: its "environment" (relative to the spec),
// or the spec's name with ".json" for ".test.json", next to it.
std::string spec_environment_path(ObjectReader& spec, const std::string& spec_path);

// A quantity from the spec, refused (with the spec file and JSON pointer) outside the
// range the command line accepts for the same value; `fallback` when absent.
double quantity_in(ObjectReader& r, std::string_view key, const ValueRange& range, std::optional<double> fallback);

std::optional<bool> optional_bool(ObjectReader& r, std::string_view key);

// The hand's stiffness, damping and mass, the noise and the seed of "options" (not
// "start", whose form depends on the dimension), into `options`.
void parse_hand_options(ObjectReader& r, HarnessOptions* options);

}  // namespace hapscene
