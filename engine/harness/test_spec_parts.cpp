// What test specs of every kind read alike (test_spec_parts.hpp).
#include "engine/harness/test_spec_parts.hpp"

#include <filesystem>

namespace hapscene {

std::string spec_environment_path(ObjectReader& spec, const std::string& spec_path) {
  const std::filesystem::path path(spec_path);
  std::string stem = path.filename().string();
  stem = stem.substr(0, stem.size() - std::string(".test.json").size());
  const auto beside = [&](const std::string& name) { return (path.parent_path() / name).lexically_normal(); };
  const auto exists = [](const std::filesystem::path& file) {
    std::error_code error;
    return std::filesystem::exists(file, error);
  };
  // The other form of the same environment: a script (.lua) for a .json, and back.
  const auto other_form = [](std::filesystem::path file) {
    return file.replace_extension(file.extension() == ".lua" ? ".json" : ".lua");
  };
  if (!spec.has("environment")) {
    // NAME.test.json tests NAME.json, or the script NAME.lua when that is what is there.
    const std::filesystem::path json = beside(stem + ".json");
    return (exists(json) || !exists(other_form(json)) ? json : other_form(json)).string();
  }
  const std::string environment = spec.string("environment");
  const std::filesystem::path named = beside(environment);
  if (!exists(named) && exists(other_form(named))) {
    spec.fail("environment", "\"" + environment + "\" does not exist (did you mean \"" +
                                 std::filesystem::path(environment).replace_extension(other_form(named).extension()).string() +
                                 "\", beside it?)");
  }
  return named.string();
}

double quantity_in(ObjectReader& r, std::string_view key, const ValueRange& range, std::optional<double> fallback) {
  const double value = fallback ? r.quantity_or(key, range.quantity, *fallback) : r.quantity(key, range.quantity);
  if (r.has(key)) {
    const std::string problem = range_problem(range, value);
    if (!problem.empty()) r.fail(key, problem);
  }
  return value;
}

std::optional<bool> optional_bool(ObjectReader& r, std::string_view key) {
  const nlohmann::json* value = r.get(key);
  if (value == nullptr) return std::nullopt;
  if (!value->is_boolean()) r.fail(key, "expected true or false, got " + json_type_name(*value));
  return value->get<bool>();
}

void parse_hand_options(ObjectReader& r, HarnessOptions* o) {
  o->hand_stiffness_N_per_m = quantity_in(r, "hand_stiffness", value_range::hand_stiffness, o->hand_stiffness_N_per_m);
  o->hand_damping_N_s_per_m = quantity_in(r, "hand_damping", value_range::hand_damping, o->hand_damping_N_s_per_m);
  o->hand_mass_kg = quantity_in(r, "hand_mass", value_range::hand_mass, o->hand_mass_kg);
  o->noise_counts = quantity_in(r, "noise", value_range::noise, o->noise_counts);
  if (r.has("seed")) o->seed = static_cast<std::uint64_t>(r.integer("seed", 0, 1LL << 53));
  else r.get("seed");
}

void SpecOutcomes::add(std::string what, bool pass, std::string message) {
  result_->outcomes.push_back({std::move(what), pass, std::move(message)});
  result_->pass = result_->pass && pass;
}

void SpecOutcomes::add_fault(const std::string& message, const std::string& line) {
  const std::size_t before = seen_.lines().size();
  seen_.add(message, "");
  if (seen_.lines().size() > before && !faults_expected_) add("/environment", false, "script fault: " + line);
}

void SpecOutcomes::add_faults(const ScriptFaultLog& log) {
  for (std::size_t i = 0; i < log.lines().size(); ++i) add_fault(log.messages()[i], log.lines()[i]);
}

}  // namespace hapscene
