// compile_script: everything that can be wrong with a script is found here, at load
// time, with a message naming the place; a run only ever sees a checked program.
#include <cctype>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/base/errors.hpp"
#include "engine/lua/script_vm.hpp"

namespace hapscene {
namespace {

// Limits come from the environment file; the loader checks them with its own JSON
// pointers, this is the last line.
void check_limits(const ScriptLimits& limits, const std::string& error_context,
                  const std::string& display_name) {
  const auto fail = [&](const std::string& what) {
    throw InputError((error_context.empty() ? display_name : error_context) +
                     ": script limits: " + what);
  };
  if (limits.instructions_per_call < 100) fail("instructions_per_call must be at least 100");
  if (limits.instructions_at_load < 100) fail("instructions_at_load must be at least 100");
  if (limits.memory_bytes < (64u << 10)) fail("memory_bytes must be at least 65536 (64 KiB)");
  if (limits.allocation_bytes_per_call < 1024) fail("allocation_bytes_per_call must be at least 1024");
  if (limits.string_bytes < 256) fail("string_bytes must be at least 256");
  if (!(limits.wall_time_per_call_s >= 0.0)) fail("wall_time_per_call_s must be 0 (off) or positive");
  if (!(limits.load_time_s > 0.0 && limits.load_time_s <= 600.0)) {
    fail("load_time_s must be positive and at most 600 s");
  }
  if (!(limits.log_messages_per_s >= 0.0)) fail("log_messages_per_s must not be negative");
}

// Number literals the compiler may have to intern: Lua's compiler looks every constant up
// in one hash table per chunk, and integer or float keys can be chosen to collide, which
// makes the compile quadratic (a 750 KB list of colliding integers took 18 s) without
// allocating, so the load deadline cannot see it. 10 000 such literals compile in about
// 0.3 s however they are chosen.
constexpr std::size_t kMaxNumberLiterals = 10'000;

// Counts number literals outside strings and comments (a lexer good enough to count).
std::size_t count_number_literals(const std::string& source) {
  const std::size_t n = source.size();
  const auto is_word = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  // The level of a long bracket "[==[" at i, or -1.
  const auto long_bracket = [&](std::size_t i) -> long {
    if (i >= n || source[i] != '[') return -1;
    std::size_t j = i + 1;
    while (j < n && source[j] == '=') ++j;
    return j < n && source[j] == '[' ? static_cast<long>(j - i - 1) : -1;
  };
  // The index after the long bracket's closing "]==]" opened at i with `level`.
  const auto skip_long = [&](std::size_t i, long level) {
    const std::string close = "]" + std::string(static_cast<std::size_t>(level), '=') + "]";
    const std::size_t end = source.find(close, i + 2 + static_cast<std::size_t>(level));
    return end == std::string::npos ? n : end + close.size();
  };
  std::size_t count = 0;
  std::size_t i = 0;
  while (i < n) {
    const char c = source[i];
    if (c == '-' && i + 1 < n && source[i + 1] == '-') {
      const long level = long_bracket(i + 2);
      if (level >= 0) {
        i = skip_long(i + 2, level);
      } else {
        while (i < n && source[i] != '\n') ++i;
      }
    } else if (c == '"' || c == '\'') {
      ++i;
      while (i < n && source[i] != c && source[i] != '\n') i += source[i] == '\\' ? 2 : 1;
      ++i;
    } else if (c == '[' && long_bracket(i) >= 0) {
      i = skip_long(i, long_bracket(i));
    } else if (std::isdigit(static_cast<unsigned char>(c)) ||
               (c == '.' && i + 1 < n && std::isdigit(static_cast<unsigned char>(source[i + 1])))) {
      ++count;
      // The literal: digits, letters (hex, exponents), dots, and a sign after an exponent.
      while (i < n && (is_word(source[i]) || source[i] == '.' ||
                       ((source[i] == '+' || source[i] == '-') &&
                        (source[i - 1] == 'e' || source[i - 1] == 'E' || source[i - 1] == 'p' ||
                         source[i - 1] == 'P')))) {
        ++i;
      }
    } else if (is_word(c)) {
      while (i < n && is_word(source[i])) ++i;  // a name (may contain digits)
    } else {
      ++i;
    }
  }
  return count;
}

}  // namespace

ScriptProgram compile_script(std::string display_name, std::string source,
                             const nlohmann::json& params_override, std::string error_context,
                             std::string pointer_prefix, ScriptLimits limits, int axes) {
  check_limits(limits, error_context, display_name);
  if (!detail::scene_axes_supported(axes)) {
    throw InputError(display_name + ": a scene of " + std::to_string(axes) + " axes cannot run scripts");
  }
  if (const std::size_t numbers = count_number_literals(source); numbers > kMaxNumberLiterals) {
    throw InputError(display_name + ": " + std::to_string(numbers) +
                     " number literals; a script may have at most " +
                     std::to_string(kMaxNumberLiterals) +
                     " (compiling many numbers can take seconds): compute large tables in code");
  }
  ScriptProgram program;
  program.display_name = std::move(display_name);
  program.source = std::move(source);
  if (!params_override.is_null()) program.params_override = std::make_shared<const nlohmann::json>(params_override);
  program.error_context = std::move(error_context);
  program.pointer_prefix = std::move(pointer_prefix);
  program.limits = limits;
  program.axes = axes;

  // One throwaway instance loads and checks the script; what it found becomes the program.
  std::unique_ptr<ScriptInstance> instance = ScriptInstance::create(program);
  const detail::ScriptVm& vm = *instance->vm_;
  program.params = vm.params;
  program.needs_velocity = vm.needs_velocity;
  program.needs_time = vm.needs_time;
  program.shapes = vm.shapes;

  // Run it once, as a run would start, so that errors inside reset() and force() on the
  // common path (typos, wrong needs, a missing return) fail the load, not the run.
  instance->reset();
  if (instance->disabled()) {
    throw InputError(std::string(instance->fault_message()) + " (while checking reset() at load)");
  }
  // The call at rest in the scene's own dimension.
  char at_rest[160];
  detail::write_state_at_rest(axes, at_rest, sizeof at_rest);
  const std::string while_checking = std::string(" (while checking force(s) at ") + at_rest + ")";
#define HAPSCENE_CALL_AT_REST(N) \
  if (axes == (N)) instance->force_N(ScriptInputOf<N>{.dt_s = 0.001});
  HAPSCENE_FOR_EACH_AXES(HAPSCENE_CALL_AT_REST)
#undef HAPSCENE_CALL_AT_REST
  if (instance->disabled()) throw InputError(std::string(instance->fault_message()) + while_checking);
  if (axes == 1) {
    // force_N keeps the first result only: a script that returns two (fx, fy) was
    // written for a 2-D scene.
    const int results = instance->check_force_results();
    if (instance->disabled()) throw InputError(std::string(instance->fault_message()) + while_checking);
    if (results != 1) {
      const std::string where = instance->vm_->short_source + ":" + std::to_string(instance->vm_->force_line);
      throw InputError(where + ": force(s) returned " + std::to_string(results) + " values, expected one number (N)" +
                       (results == 2 ? ": this is a 1-D scene, and a 2-D script returns two, fx, fy "
                                       "(docs/reference/lua.md, \"Scripts in 2-D\")"
                                     : "") +
                       while_checking);
    }
    // Declared shapes describe a 2-D script for validate; a script that passed the 1-D
    // checks is a 1-D script, and a 1-D scene has no use for them.
    if (!program.shapes.empty()) {
      throw InputError(program.display_name +
                       ": shapes: this is a 1-D scene, and shapes are for 2-D scripts (validate presses into "
                       "them in a 2-DOF scene; a 1-D scene's walls are found by a scan of the field): remove "
                       "shapes, or use the script in a planar environment");
    }
  }
  return program;
}

}  // namespace hapscene
