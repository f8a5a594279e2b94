// JSON keys of the script effect: where the script is, its parameter overrides and its
// limits. The script itself is compiled (and run once) here, at load time, so syntax
// errors, unknown parameters and typos inside force() fail the load.
#include "engine/effects/script_effect.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/base/json_source.hpp"
#include "engine/base/object_reader.hpp"
#include "engine/base/physical_ranges.hpp"
#include "engine/lua/log_queue.hpp"

namespace hapscene {

inline constexpr std::size_t kMaxScriptBytes = 1u << 20;

ScriptLimits parse_script_limits(ObjectReader& reader) {
  ScriptLimits limits;
  limits.instructions_per_call = reader.integer_or("instructions_per_call", 100, 100'000'000,
                                                   limits.instructions_per_call);
  limits.memory_bytes = static_cast<std::size_t>(
      reader.integer_or("memory_bytes", 64 << 10, 1ll << 30, static_cast<long long>(limits.memory_bytes)));
  limits.allocation_bytes_per_call = static_cast<std::size_t>(reader.integer_or(
      "allocation_bytes_per_call", 1 << 10, 1ll << 30, static_cast<long long>(limits.allocation_bytes_per_call)));
  limits.wall_time_per_call_s =
      reader.quantity_or("wall_time_per_call", Quantity::time_s, limits.wall_time_per_call_s, ranges::kDuration_s);
  limits.instructions_at_load = reader.integer_or("instructions_at_load", 100, 1'000'000'000,
                                                  limits.instructions_at_load);
  limits.string_bytes = static_cast<std::size_t>(
      reader.integer_or("string_bytes", 256, 16 << 20, static_cast<long long>(limits.string_bytes)));
  limits.load_time_s =
      reader.quantity_or("load_time", Quantity::time_s, limits.load_time_s, Bound::positive);
  if (limits.load_time_s > 600.0) reader.fail("load_time", "must be at most 600 s");
  // One message per tick at the highest tick rate.
  limits.log_messages_per_s =
      reader.quantity_or("log_rate", Quantity::frequency_Hz, limits.log_messages_per_s, Range{0.0, 1e5});
  limits.log_burst = static_cast<std::size_t>(reader.integer_or(
      "log_burst", 0, static_cast<long long>(detail::LogQueue::kSlots), static_cast<long long>(limits.log_burst)));
  reader.finish();
  return limits;
}

ScriptLoadBudget plan_script_loads(const nlohmann::json& effects, const std::string& file,
                                   const std::string& pointer) {
  ScriptLoadBudget budget{kScriptLoadBudget_s, 0.0};
  std::size_t scripts = 0;
  std::size_t memory_bytes = 0;
  for (std::size_t i = 0; i < effects.size(); ++i) {
    const nlohmann::json& effect = effects[i];
    if (!effect.is_object()) continue;
    const auto type = effect.find("type");
    const auto enabled = effect.find("enabled");
    if (type == effect.end() || *type != "script") continue;
    if (enabled != effect.end() && *enabled == false) continue;
    const std::string at = json_pointer_append(pointer, i);
    if (++scripts > kMaxScriptEffects) {
      throw InputError(located_message(file, at, "more than " + std::to_string(kMaxScriptEffects) +
                                                     " script effects in one environment (each has its own Lua state)"));
    }
    ScriptLimits limits;
    const auto block = effect.find("limits");
    if (block != effect.end() && block->is_object()) {
      try {
        ObjectReader limits_reader(*block, json_pointer_append(at, "limits"), file);
        limits = parse_script_limits(limits_reader);
      } catch (const InputError&) {
        continue;  // the effect's own parse reports it, after the effects before it
      }
    }
    memory_bytes += limits.memory_bytes;
    if (memory_bytes > kMaxScriptMemoryBytesTotal) {
      const bool written = block != effect.end() && block->contains("memory_bytes");
      throw InputError(located_message(
          file, written ? json_pointer_append(json_pointer_append(at, "limits"), "memory_bytes") : at,
          "the script effects' memory_bytes add up to " + std::to_string(memory_bytes) + " here, more than the " +
              std::to_string(kMaxScriptMemoryBytesTotal) + " (1 GiB) one environment may have"));
    }
    budget.total_s = std::max(budget.total_s, limits.load_time_s);
  }
  return budget;
}

ScriptEffect ScriptEffect::parse(ObjectReader& reader, ScriptLoadBudget& budget, int axes) {
  // Where the script is: a file relative to the environment, or inline source.
  const bool has_file = reader.has("file");
  const bool has_source = reader.has("source");
  if (has_file == has_source) reader.fail("", "a script needs exactly one of \"file\" and \"source\"");
  std::string display_name;
  std::string raw_path;
  std::string source;
  if (has_file) {
    std::filesystem::path path(reader.string("file"));
    if (path.is_relative()) path = std::filesystem::path(reader.base_dir()) / path;
    raw_path = path.lexically_normal().string();
    // Messages name the file in printable form (engine/base/format.hpp); the reload
    // watcher keeps the path as it is.
    display_name = printable(raw_path);
    try {
      source = read_text_file(raw_path, kMaxScriptBytes);
    } catch (const InputError& error) {
      reader.fail("file", error.what());
    }
    reader.get("source");
  } else {
    source = reader.string("source");
    display_name = printable(reader.file() + "#" + reader.pointer_to("source"));
    reader.get("file");
  }

  // Parameter overrides and limits.
  nlohmann::json params = nlohmann::json::object();
  if (const nlohmann::json* value = reader.get("params")) {
    if (!value->is_object()) reader.fail("params", "expected an object, got " + json_type_name(*value));
    params = *value;
  }
  ScriptLimits limits;
  if (const nlohmann::json* value = reader.get("limits")) {
    ObjectReader limits_reader(*value, reader.pointer_to("limits"), reader.file(), reader.base_dir());
    limits = parse_script_limits(limits_reader);
  }

  // The load may take its own load_time, or what is left of the environment's budget.
  ScriptLimits load_limits = limits;
  const auto shared_budget = [&] {
    return "the script effects of this environment share " + format_number(budget.total_s) +
           " s to load (the larger of " + format_number(kScriptLoadBudget_s) + " s and their largest load_time)";
  };
  const double left_s = budget.total_s - budget.used_s;
  if (left_s <= 0.0) reader.fail("", shared_budget() + ", and the scripts before this one used it all");
  load_limits.load_time_s = std::min(load_limits.load_time_s, left_s);
  ScriptEffect effect;
  if (has_file) effect.file = raw_path;
  const auto started = std::chrono::steady_clock::now();
  const auto charge = [&] {
    const double took_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    budget.used_s += took_s;
    return took_s;
  };
  try {
    ScriptProgram program = compile_script(display_name, std::move(source), params, reader.file(),
                                           reader.pointer_to("params"), load_limits, axes);
    program.limits = limits;  // each run's instance has the script's own load_time
    effect.program = std::make_shared<const ScriptProgram>(std::move(program));
    charge();
  } catch (const InputError& error) {
    const double took_s = charge();
    const std::string message = error.what();
    // Stopped by the shared budget rather than by its own load_time.
    if (left_s < limits.load_time_s && took_s >= left_s) {
      reader.fail("", shared_budget() + ", and this one was stopped when it ran out: " + message);
    }
    // An error inside a referenced script file: "env.json: /effects/0/file: s.lua:12: ...".
    if (has_file && message.starts_with(display_name + ":")) reader.fail("file", message);
    throw;
  }
  effect.needs.velocity = effect.program->needs_velocity;
  effect.needs.time = effect.program->needs_time;
  return effect;
}

}  // namespace hapscene
