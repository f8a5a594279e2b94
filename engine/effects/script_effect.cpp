// JSON keys of the script effect: where the script is, its parameter overrides and its
// limits. The script itself is compiled (and run once) here, at load time, so syntax
// errors, unknown parameters and typos inside force() fail the load.
#include "engine/effects/script_effect.hpp"

#include <filesystem>

#include "engine/core/errors.hpp"
#include "engine/core/format.hpp"
#include "engine/load/json_source.hpp"
#include "engine/load/object_reader.hpp"
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
      reader.quantity_or("wall_time_per_call", Quantity::time_s, limits.wall_time_per_call_s, Bound::non_negative);
  limits.instructions_at_load = reader.integer_or("instructions_at_load", 100, 1'000'000'000,
                                                  limits.instructions_at_load);
  limits.string_bytes = static_cast<std::size_t>(
      reader.integer_or("string_bytes", 256, 16 << 20, static_cast<long long>(limits.string_bytes)));
  limits.load_time_s =
      reader.quantity_or("load_time", Quantity::time_s, limits.load_time_s, Bound::positive);
  if (limits.load_time_s > 600.0) reader.fail("load_time", "must be at most 600 s");
  limits.log_messages_per_s =
      reader.quantity_or("log_rate", Quantity::frequency_Hz, limits.log_messages_per_s, Bound::non_negative);
  limits.log_burst = static_cast<std::size_t>(reader.integer_or(
      "log_burst", 0, static_cast<long long>(detail::LogQueue::kSlots), static_cast<long long>(limits.log_burst)));
  reader.finish();
  return limits;
}

ScriptEffect ScriptEffect::parse(ObjectReader& reader) {
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
    // Messages name the file in printable form (engine/core/format.hpp); the reload
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

  ScriptEffect effect;
  if (has_file) effect.file = raw_path;
  try {
    effect.program = std::make_shared<const ScriptProgram>(compile_script(
        display_name, std::move(source), params, reader.file(), reader.pointer_to("params"), limits));
  } catch (const InputError& error) {
    // An error inside a referenced script file: "env.json: /effects/0/file: s.lua:12: ...".
    const std::string message = error.what();
    if (has_file && message.starts_with(display_name + ":")) reader.fail("file", message);
    throw;
  }
  effect.needs.velocity = effect.program->needs_velocity;
  effect.needs.time = effect.program->needs_time;
  return effect;
}

}  // namespace hapscene
