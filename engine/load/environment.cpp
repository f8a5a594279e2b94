#include "engine/load/environment.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <utility>
#include <variant>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/base/json_source.hpp"
#include "engine/base/object_reader.hpp"
#include "engine/base/physical_ranges.hpp"
#include "engine/base/type_hint.hpp"
#include "engine/devices/planar/planar_profile.hpp"
#include "engine/effects/declared_parse.hpp"
#include "engine/effects/planar/planar_effect_types.hpp"
#include "engine/effects/vector_reader.hpp"
#include "engine/load/effect_warnings.hpp"
#include "engine/load/validate_block.hpp"

namespace hapscene {
namespace {

inline constexpr double kMinRate_Hz = 10.0;
inline constexpr double kMaxRate_Hz = 100000.0;
// Effects in one environment (enabled or not), checked before any is read: far beyond any
// lab scene, and it bounds the work and memory of a load (script effects have their own,
// lower bound: kMaxScriptEffects).
inline constexpr std::size_t kMaxEffects = 256;

// Built-in effect types by their "type" name.
// Script effects also take the environment's shared load budget.
struct EffectType {
  std::string_view name;
  std::function<Effect(ObjectReader&, ScriptLoadBudget*)> parse;
};

template <typename T>
EffectType effect_type() {
  return EffectType{T::kType, [](ObjectReader& reader, ScriptLoadBudget* budget) {
                      if constexpr (std::is_same_v<T, ScriptEffect>) {
                        return Effect{T::parse(reader, *budget)};
                      } else {
                        return Effect{parse_declared<T>(reader)};
                      }
                    }};
}

// Every alternative of Effect, in its order.
const std::vector<EffectType>& effect_types() {
  static const std::vector<EffectType> types = []<std::size_t... I>(std::index_sequence<I...>) {
    return std::vector<EffectType>{effect_type<std::variant_alternative_t<I, Effect>>()...};
  }(std::make_index_sequence<std::variant_size_v<Effect>>{});
  return types;
}

// One element of "effects". Returns false when it is disabled ("enabled": false): then
// it is not compiled at all (a disabled script is not even loaded).
bool parse_effect(const nlohmann::json& value, const std::string& pointer, const std::string& file,
                  const std::string& base_dir, ScriptLoadBudget* budget, Effect* effect) {
  ObjectReader reader(value, pointer, file, base_dir);
  std::vector<std::string_view> names;
  for (const EffectType& type : effect_types()) names.push_back(type.name);

  const std::string type_name = reader.string("type");
  const auto type = std::find_if(effect_types().begin(), effect_types().end(),
                                 [&](const EffectType& t) { return t.name == type_name; });
  if (type == effect_types().end()) {
    reader.fail("type", "unknown effect type \"" + type_name + "\"" + effect_type_hint(type_name, names));
  }
  bool enabled = true;
  if (const nlohmann::json* flag = reader.get("enabled")) {
    if (!flag->is_boolean()) reader.fail("enabled", "expected a boolean, got " + json_type_name(*flag));
    enabled = flag->get<bool>();
  }
  if (!enabled) return false;
  *effect = type->parse(reader, budget);
  reader.finish();
  return true;
}

// The limits every "safety" block has, whatever the scene's axes: the force limit, the
// slew limit and the soft start, each only safer than the device's (`device` a profile's
// DeviceLimits or PlanarLimits).
template <int N, typename Limits>
void parse_common_safety(ObjectReader& reader, const Limits& device, SafetyConfigOf<N>* safety) {
  const auto lower_or_equal = [&](std::string_view key, double value, double device_value,
                                  const char* unit) {
    if (value > device_value) {
      reader.fail(key, "must not exceed the device's " + format_number(device_value) + " " + unit);
    }
    return value;
  };
  safety->max_force_N = lower_or_equal(
      "max_force", reader.quantity_or("max_force", Quantity::force_N, device.max_force_N, Bound::positive),
      device.max_force_N, "N");
  safety->slew_limit_N_per_s = lower_or_equal(
      "slew_limit",
      reader.quantity_or("slew_limit", Quantity::force_rate_N_per_s, device.slew_limit_N_per_s,
                         Bound::positive),
      device.slew_limit_N_per_s, "N/s");
  safety->soft_start_s = reader.quantity_or("soft_start", Quantity::time_s, device.soft_start_s,
                                            ranges::kDuration_s);
  if (safety->soft_start_s < device.soft_start_s) {
    reader.fail("soft_start", "must not be shorter than the device's " +
                                  format_number(device.soft_start_s) + " s");
  }
}

// The environment's "safety" block: each limit may only be made safer than the device's.
void parse_safety(ObjectReader& reader, const DeviceLimits& device, SafetyConfig* safety) {
  parse_common_safety(reader, device, safety);
  if (reader.has("workspace")) {
    const auto [low_m, high_m] = reader.range("workspace", Quantity::length_m);
    if (low_m < device.workspace_min_m || high_m > device.workspace_max_m) {
      reader.fail("workspace", "must lie within the device's workspace [" +
                                   format_number(device.workspace_min_m) + ", " +
                                   format_number(device.workspace_max_m) + "] m");
    }
    safety->workspace_min_m = low_m;
    safety->workspace_max_m = high_m;
  } else {
    reader.get("workspace");
  }
  reader.finish();
}

VelocityEstimatorConfig parse_velocity(ObjectReader& reader) {
  VelocityEstimatorConfig config;
  const std::string name = reader.choice(
      "estimator", {kVelocityEstimatorNames[0], kVelocityEstimatorNames[1],
                    kVelocityEstimatorNames[2], kVelocityEstimatorNames[3]},
      std::string(kVelocityEstimatorNames[0]));
  for (std::size_t i = 0; i < std::size(kVelocityEstimatorNames); ++i) {
    if (kVelocityEstimatorNames[i] == name) config.kind = static_cast<VelocityEstimatorKind>(i);
  }
  config.cutoff_Hz =
      reader.quantity_or("cutoff", Quantity::frequency_Hz, config.cutoff_Hz, ranges::kCutoff_Hz);
  reader.finish();
  return config;
}

// What every scene reads first, whatever its axes: name, rate, the device profile (by
// name, shipped, or by path relative to the file, loaded by `load_profile`).
template <int N, typename LoadProfile>
void compile_header(ObjectReader& reader, const std::string& file, const std::string& base_dir,
                    LoadProfile load_profile, SceneOf<N>* scene) {
  scene->source_path = file;
  // Printed by every command and in reports: printable (engine/base/format.hpp), so a
  // name holding "\n" or "\r" cannot forge an output line.
  scene->name = printable(reader.string_or("name", std::filesystem::path(file).stem().string()));
  reader.string_or("description", "");  // for people: checked to be text, not kept

  // Tick rate.
  scene->rate_hz = reader.quantity_or("rate_hz", Quantity::frequency_Hz, 1000.0, Bound::positive);
  if (scene->rate_hz < kMinRate_Hz || scene->rate_hz > kMaxRate_Hz) {
    reader.fail("rate_hz", "must be between 10 Hz and 100 kHz");
  }
  scene->period_s = 1.0 / scene->rate_hz;

  const std::string device_name = reader.string_or("device", "hapkit3");
  try {
    scene->device = load_profile(device_name, base_dir);
  } catch (const InputError& error) {
    // "env.json: /device: profile.json:3:7: ...": the referring place, then the profile's own.
    reader.fail("device", error.what());
  }
  const bool device_is_path = device_name.find('/') != std::string::npos || device_name.ends_with(".json");
  scene->device_file = device_is_path && std::filesystem::path(device_name).is_relative()
                           ? (std::filesystem::path(base_dir) / device_name).lexically_normal().string()
                           : device_name;
}

// The "velocity" block (optional), and the low-pass factor for the scene's period.
template <int N>
void compile_velocity(ObjectReader& reader, SceneOf<N>* scene) {
  if (const nlohmann::json* velocity = reader.get("velocity")) {
    ObjectReader velocity_reader(*velocity, reader.pointer_to("velocity"), reader.file());
    scene->velocity = parse_velocity(velocity_reader);
  }
  scene->velocity.lowpass_alpha = lowpass_alpha_for(scene->velocity.cutoff_Hz, scene->period_s);
}

// The "effects" array: present, an array, within the count limit.
const nlohmann::json& effects_array(ObjectReader& reader) {
  const nlohmann::json* effects = reader.get("effects");
  if (effects == nullptr) reader.fail_missing("effects");
  if (!effects->is_array()) {
    reader.fail("effects", "expected an array of effects, got " + json_type_name(*effects));
  }
  if (effects->size() > kMaxEffects) {
    reader.fail("effects", "has " + std::to_string(effects->size()) + " effects; one environment may have at most " +
                               std::to_string(kMaxEffects));
  }
  return *effects;
}

// A planar scene's "safety" block: force and slew limits, soft start, and the workspace
// as a box ({"min": [x, y], "max": [x, y]}) within the device's; each only safer than the
// device's. The box narrows the device's workspace and never replaces it: the tick tests
// the box and, when the device's workspace is a polygon, the polygon as well.
void parse_planar_safety(ObjectReader& reader, const PlanarLimits& device, SafetyConfigOf<2>* safety) {
  parse_common_safety(reader, device, safety);
  if (const nlohmann::json* workspace = reader.get("workspace")) {
    ObjectReader box(*workspace, reader.pointer_to("workspace"), reader.file());
    const Vec2 min_m = read_vector(box, "min", Quantity::length_m, ranges::kPosition_m);
    const Vec2 max_m = read_vector(box, "max", Quantity::length_m, ranges::kPosition_m);
    box.finish();
    if (!(min_m[0] < max_m[0] && min_m[1] < max_m[1])) {
      reader.fail("workspace", "min must be below max on both axes");
    }
    const std::string outside = box_leaves_workspace(device.workspace, min_m, max_m);
    if (!outside.empty()) reader.fail("workspace", "must lie within the device's workspace: " + outside);
    // The intersection: the box within the device's box (or the polygon's bounding box);
    // the device's polygon, if any, stays in safety->workspace_polygon_m.
    for (int i = 0; i < 2; ++i) {
      safety->workspace_min_m[i] = std::max(safety->workspace_min_m[i], min_m[i]);
      safety->workspace_max_m[i] = std::min(safety->workspace_max_m[i], max_m[i]);
    }
  }
  reader.finish();
}

// The device's workspace as the tick tests it: its bounding box, and the polygon if any.
void set_planar_workspace(const PlanarWorkspace& workspace, SafetyConfigOf<2>* safety) {
  workspace_bounds(workspace, &safety->workspace_min_m, &safety->workspace_max_m);
  if (!workspace.is_box) safety->workspace_polygon_m = workspace.polygon_m;
}

// What loading differs in per device kind: the profile, the compiled device model, the
// device's own safety limits and the "safety" block over them, the effects' parser and the
// "validate" block's keys. One specialisation per N of HAPSCENE_FOR_EACH_AXES; compile<N>
// below is written once.
template <int N>
struct KindLoad;

// One axis: the capstan devices (the Hapkit), the lab effects.
template <>
struct KindLoad<1> {
  // A planar profile here is a 2-DOF scene given to a command that takes 1-DOF ones.
  static DeviceProfile load_profile(const std::string& name, const std::string& dir) {
    if (names_planar_profile(name, dir)) {
      throw InputError("\"" + name + "\" is a 2-DOF (planar) profile: this command takes 1-DOF scenes only so far "
                       "(2-DOF scenes: probe, run, plot and validate)");
    }
    return load_device_profile(name, dir);
  }
  static DeviceModel compile_model(const DeviceProfile& device) { return compile_device_model(device); }
  static void device_safety(const DeviceProfile& device, SafetyConfig* safety) {
    const DeviceLimits& limits = device.limits;
    *safety = SafetyConfig{limits.max_force_N,     limits.slew_limit_N_per_s, limits.workspace_min_m,
                           limits.workspace_max_m, limits.soft_start_s,       limits.soft_start_threshold_N};
  }
  static void parse_safety_block(ObjectReader& reader, const DeviceProfile& device, SafetyConfig* safety) {
    parse_safety(reader, device.limits, safety);
  }
  static bool parse_effect_at(const nlohmann::json& value, const std::string& pointer, const std::string& file,
                              const std::string& base_dir, ScriptLoadBudget* budget, Effect* effect) {
    return parse_effect(value, pointer, file, base_dir, budget, effect);
  }
  static void parse_validate(ObjectReader& reader, ValidateThresholds* thresholds) {
    parse_validate_block(reader, thresholds);
  }
};

// Two axes: the planar linkages (the Haplink, pantographs, the Haply 2DIY), the 2-D effects.
template <>
struct KindLoad<2> {
  static PlanarProfile load_profile(const std::string& name, const std::string& dir) {
    return load_planar_profile(name, dir);
  }
  static PlanarTickModel compile_model(const PlanarProfile& device) { return compile_planar_tick_model(device); }
  static void device_safety(const PlanarProfile& device, SafetyConfigOf<2>* safety) {
    const PlanarLimits& limits = device.limits;
    safety->max_force_N = limits.max_force_N;
    safety->slew_limit_N_per_s = limits.slew_limit_N_per_s;
    safety->soft_start_s = limits.soft_start_s;
    safety->soft_start_threshold_N = limits.soft_start_threshold_N;
    set_planar_workspace(limits.workspace, safety);
  }
  static void parse_safety_block(ObjectReader& reader, const PlanarProfile& device, SafetyConfigOf<2>* safety) {
    parse_planar_safety(reader, device.limits, safety);
  }
  static bool parse_effect_at(const nlohmann::json& value, const std::string& pointer, const std::string& file,
                              const std::string& base_dir, ScriptLoadBudget* budget, PlanarEffect* effect) {
    return parse_planar_effect(value, pointer, file, effect, base_dir, budget);
  }
  static void parse_validate(ObjectReader& reader, ValidateThresholds* thresholds) {
    parse_planar_validate_block(reader, thresholds);
  }
};

// An environment's JSON, compiled for a device of N axes: the header, the device's model
// and safety limits lowered by the file's, velocity, the effects (script effects share one
// load budget), and the harness's thresholds (checked at every load, not part of the scene).
template <int N>
EnvironmentOf<N> compile(const nlohmann::json& root, const std::string& file, const std::string& base_dir) {
  using Kind = KindLoad<N>;
  ObjectReader reader(root, "", file);
  EnvironmentOf<N> environment;
  SceneOf<N>& scene = environment.scene;
  compile_header(reader, file, base_dir, &Kind::load_profile, &scene);
  scene.device_model = Kind::compile_model(scene.device);

  // Safety: the device's limits, lowered by the environment's.
  Kind::device_safety(scene.device, &scene.safety);
  if (const nlohmann::json* safety = reader.get("safety")) {
    ObjectReader safety_reader(*safety, reader.pointer_to("safety"), file);
    Kind::parse_safety_block(safety_reader, scene.device, &scene.safety);
  }
  finalise_safety(scene.period_s, &scene.safety);
  compile_velocity(reader, &scene);

  // Effects, and what they need.
  const nlohmann::json& effects = effects_array(reader);
  ScriptLoadBudget script_budget = plan_script_loads(effects, file, reader.pointer_to("effects"));
  for (std::size_t i = 0; i < effects.size(); ++i) {
    typename SceneParts<N>::Effects::Variant effect;
    const std::string pointer = json_pointer_append(reader.pointer_to("effects"), i);
    if (Kind::parse_effect_at(effects[i], pointer, file, base_dir, &script_budget, &effect)) {
      std::string warning = inert_effect_warning(effect, effects[i], scene);
      if (!warning.empty()) scene.load_warnings.push_back(printable(file + ": " + pointer + " " + warning));
      add_effect(&scene, std::move(effect));
    }
  }

  // Thresholds for the harness (hapscene validate): not part of the scene.
  if (const nlohmann::json* validate = reader.get("validate")) {
    ObjectReader validate_reader(*validate, reader.pointer_to("validate"), file);
    Kind::parse_validate(validate_reader, &environment.validate);
  }
  reader.finish();
  return environment;
}

// The "device" an environment's JSON names (default "hapkit3"), without checking more.
std::string device_named(const nlohmann::json& root) {
  if (root.is_object()) {
    const auto device = root.find("device");
    if (device != root.end() && device->is_string()) return device->get<std::string>();
  }
  return "hapkit3";
}

}  // namespace

namespace {

// A user's file: its warnings go to stderr at every load, whatever the command (scenes a
// command builds from its own text, such as the bench's, keep theirs in the scene).
template <int N>
void print_warnings(const EnvironmentOf<N>& loaded) {
  for (const std::string& warning : loaded.scene.load_warnings) std::fprintf(stderr, "warning: %s\n", warning.c_str());
}

// The folder relative paths in a file are taken from.
std::string base_dir_of(const std::string& path) {
  const std::filesystem::path file(path);
  return file.parent_path().empty() ? "." : file.parent_path().string();
}

// The number of axes of the device a parsed environment names.
int axes_of(const nlohmann::json& root, const std::string& base_dir) {
  return names_planar_profile(device_named(root), base_dir) ? 2 : 1;
}

// A parsed environment compiled for the N of its device (one of HAPSCENE_FOR_EACH_AXES).
AnyEnvironment compile_any(const nlohmann::json& root, const std::string& display_name, const std::string& base_dir) {
  const int axes = axes_of(root, base_dir);
  std::optional<AnyEnvironment> environment;
#define HAPSCENE_COMPILE_FOR(N) \
  if (axes == (N)) environment.emplace(std::in_place_type<EnvironmentOf<N>>, compile<N>(root, display_name, base_dir));
  HAPSCENE_FOR_EACH_AXES(HAPSCENE_COMPILE_FOR)
#undef HAPSCENE_COMPILE_FOR
  return std::move(*environment);
}

}  // namespace

template <int N>
EnvironmentOf<N> compile_environment_of(std::string_view json_text, const std::string& display_name,
                                        const std::string& base_dir) {
  return compile<N>(parse_json_text(json_text, display_name), display_name, base_dir);
}

template <int N>
EnvironmentOf<N> load_environment_of(const std::string& path) {
  EnvironmentOf<N> loaded = compile_environment_of<N>(environment_text_of(path), path, base_dir_of(path));
  print_warnings(loaded);
  return loaded;  // moved, not copied
}

AnyEnvironment compile_any_environment(std::string_view json_text, const std::string& display_name,
                                       const std::string& base_dir) {
  return compile_any(parse_json_text(json_text, display_name), display_name, base_dir);
}

AnyEnvironment load_any_environment(const std::string& path) {
  AnyEnvironment loaded = compile_any_environment(environment_text_of(path), path, base_dir_of(path));
  std::visit([](const auto& environment) { print_warnings(environment); }, loaded);
  return loaded;
}

int axes_of(const AnyEnvironment& environment) {
  return std::visit([](const auto& loaded) { return std::decay_t<decltype(loaded)>::kAxes; }, environment);
}

int environment_axes(const std::string& path) {
  const std::filesystem::path file(path);
  if (file.extension() == ".lua") return 1;  // a script alone: the Hapkit
  return environment_text_axes(read_text_file(path, kMaxJsonFileBytes), path, base_dir_of(path));
}

int environment_text_axes(std::string_view json_text, const std::string& display_name, const std::string& base_dir) {
  return axes_of(parse_json_text(json_text, display_name), base_dir);
}

std::string environment_text_of(const std::string& path) {
  const std::filesystem::path file(path);
  if (file.extension() != ".lua") return read_text_file(path, kMaxJsonFileBytes);
  // A .lua file is a one-effect environment with the script's default parameters.
  check_readable_file(path);  // never opened here: a named pipe would block
  const nlohmann::json script = nlohmann::json::object({{"type", "script"}, {"file", file.filename().string()}});
  const nlohmann::json root =
      nlohmann::json::object({{"name", file.stem().string()}, {"effects", nlohmann::json::array({script})}});
  return root.dump(2) + "\n";
}

#define HAPSCENE_ENVIRONMENT_LOADS(N)                                                                          \
  template EnvironmentOf<N> compile_environment_of<N>(std::string_view, const std::string&, const std::string&); \
  template EnvironmentOf<N> load_environment_of<N>(const std::string&);
HAPSCENE_FOR_EACH_AXES(HAPSCENE_ENVIRONMENT_LOADS)
#undef HAPSCENE_ENVIRONMENT_LOADS

}  // namespace hapscene
