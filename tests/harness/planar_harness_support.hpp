#pragma once
// What the 2-D harness tests share: a shipped environment by name, and a scenario's check
// by name.
#include <string>

#include "engine/harness/planar_validate.hpp"
#include "engine/load/environment.hpp"

namespace hapscene::test {

// environments/planar/<name>.json, loaded.
inline PlanarScene shipped_planar(const std::string& name) {
  return load_planar_environment_file(std::string(HAPSCENE_SOURCE_DIR) + "/environments/planar/" + name + ".json");
}

// The scenario's check called `name`, or nullptr.
inline const CheckResult* check_named(const PlanarScenarioResult& result, const std::string& name) {
  for (const CheckResult& c : result.checks) {
    if (c.name == name) return &c;
  }
  return nullptr;
}

}  // namespace hapscene::test
