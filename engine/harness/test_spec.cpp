#include "engine/harness/test_spec.hpp"

#include <algorithm>
#include <exception>
#include <filesystem>
#include <optional>

#include "engine/base/errors.hpp"
#include "engine/base/json_source.hpp"
#include "engine/base/object_reader.hpp"
#include "engine/harness/pace.hpp"
#include "engine/harness/test_spec_kind.hpp"
#include "engine/load/environment.hpp"

namespace hapscene {
namespace {

// The environment a spec names, loaded once (its N picks the spec's format), or why it
// could not be: the spec is then read in the format of the N its device names (1 when
// even that cannot be told), so a problem in the spec itself is still the one reported
// first, and the load's error after it, named from the spec's "/environment".
struct SpecEnvironment {
  std::optional<AnyEnvironment> loaded;
  std::exception_ptr load_error;
  int axes = 1;
};

SpecEnvironment load_spec_environment(const nlohmann::json& root, const std::string& spec_path) {
  SpecEnvironment out;
  std::string environment_path;
  try {
    ObjectReader r(root, "", spec_path);
    environment_path = spec_environment_path(r, spec_path);
  } catch (const InputError&) {
    return out;  // the spec's own problem: parse_spec reports it
  }
  try {
    out.loaded.emplace(load_any_environment(environment_path));
    out.axes = axes_of(*out.loaded);
  } catch (const InputError&) {
    out.load_error = std::current_exception();
    try {
      out.axes = environment_axes(environment_path);
    } catch (const InputError&) {
    }
  }
  return out;
}

// Reads the spec for an environment of N axes, and judges it on `environment` (nullptr:
// the load failed, `load_error` says why).
template <int N>
void run_spec_of(const nlohmann::json& root, const std::string& spec_path, const EnvironmentOf<N>* environment,
                 const std::exception_ptr& load_error, SpecResult* result) {
  const SpecOf<N> spec = parse_spec<N>(root, spec_path);
  result->environment_path = spec.environment_path;
  if (environment == nullptr) {
    try {
      std::rethrow_exception(load_error);
    } catch (const InputError& error) {
      throw InputError(spec_path + ": /environment: " + error.what());
    }
  }
  run_spec(spec_path, spec, *environment, result);
}

}  // namespace

SpecResult run_test_spec(const std::string& spec_path) {
  SpecResult result;
  result.spec_path = spec_path;
  try {
    // The spec's JSON, read once (InputError, located, when it is not JSON).
    const nlohmann::json root = read_json_file(spec_path);
    const SpecEnvironment environment = load_spec_environment(root, spec_path);
    if (environment.loaded) {
      std::visit([&](const auto& loaded) { run_spec_of(root, spec_path, &loaded, nullptr, &result); },
                 *environment.loaded);
    } else {
#define HAPSCENE_RUN_SPEC_OF(N) \
  if (environment.axes == (N)) run_spec_of<N>(root, spec_path, nullptr, environment.load_error, &result);
      HAPSCENE_FOR_EACH_AXES(HAPSCENE_RUN_SPEC_OF)
#undef HAPSCENE_RUN_SPEC_OF
    }
  } catch (const ScriptsTooSlow& slow) {
    // Scripts an open-loop scan found too slow for the loop's checks (ScanPace): the spec
    // fails with the pace message alone, as when their first calls are too slow.
    result.outcomes.clear();
    result.pass = true;
    SpecOutcomes(&result, false).add("/environment", false, slow.what());
  }
  return result;
}

std::vector<std::string> find_test_specs(const std::vector<std::string>& folders) {
  std::vector<std::string> specs;
  for (const std::string& folder : folders) {
    std::error_code error;
    if (!std::filesystem::is_directory(folder, error)) continue;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(
             folder, std::filesystem::directory_options::skip_permission_denied, error)) {
      const std::string name = entry.path().filename().string();
      if (entry.is_regular_file() && name.size() > 10 && name.ends_with(".test.json")) {
        specs.push_back(entry.path().lexically_normal().string());
      }
    }
  }
  std::sort(specs.begin(), specs.end());
  return specs;
}

}  // namespace hapscene
