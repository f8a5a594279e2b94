#pragma once
// Environment test specs (`environments/<name>.test.json`, format in docs/reference/test-specs.md): what an environment should feel like, checked by `hapscene test`.
#include <string>
#include <vector>

namespace hapscene {

// One stated expectation and whether the environment met it.
struct SpecOutcome {
  std::string what;     // JSON pointer of the expectation in the spec: "/forces/1"
  bool pass{};
  std::string message;  // what was expected and what was found
};

struct SpecResult {
  std::string spec_path;
  std::string environment_path;
  std::vector<SpecOutcome> outcomes;
  bool pass{true};
};

// Loads the spec and its environment (InputError, located, for anything invalid), then
// probes, validates and compares. The environment's N picks the spec's format: a 2-DOF
// scene's spec takes vectors and regions (docs/reference/test-specs.md, "Test specs in
// 2-D"; test_spec_kind.hpp).
SpecResult run_test_spec(const std::string& spec_path);

// Every *.test.json under the given folders (recursively), sorted.
std::vector<std::string> find_test_specs(const std::vector<std::string>& folders);

}  // namespace hapscene
