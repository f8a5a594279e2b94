// A script instance: one sandboxed lua_State per run. Creation runs the whole load
// sequence (sandbox, text-only chunk, top-level code, checks); the calls in the tick
// (force_N, reset) run under the instruction budget and allocation limits and turn any
// failure into "disabled, 0 N, one message".
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/lua/bytecode.hpp"
#include "engine/lua/script_vm.hpp"

namespace hapscene {
namespace {

using detail::ScriptVm;

// Each incremental GC step does about 2^10 bytes' worth of collector work.
constexpr int kGcStepSizeLog2 = 10;

// What Lua prints as the chunk name of "@" + display_name (LUA_IDSIZE = 60).
std::string short_source_of(const std::string& display_name) {
  constexpr std::size_t kRoom = LUA_IDSIZE - 1;
  if (display_name.size() <= kRoom) return display_name;
  return "..." + display_name.substr(display_name.size() - (kRoom - 3));
}

// A message with the script's place: Lua's own messages start with "short_src:line:";
// others get "display_name: " in front.
bool has_place(const ScriptVm& vm, const char* message) {
  const std::size_t n = vm.short_source.size();
  return std::strncmp(message, vm.short_source.c_str(), n) == 0 && message[n] == ':';
}

// After a failed load step: the first of the load error, the tripped limit, or Lua's message.
// The message is made printable (a script's error("...") may hold newlines or a NUL).
[[noreturn]] void throw_load_failure(const ScriptVm& vm, lua_State* L) {
  if (!vm.load_error.empty()) throw InputError(printable(vm.load_error));
  if (vm.fault_length > 0) throw InputError(std::string(vm.fault, vm.fault_length));
  if (lua_type(L, -1) == LUA_TSTRING) {
    std::size_t length = 0;
    const char* text = lua_tolstring(L, -1, &length);
    const std::string message(text, length);
    char hint[160];
    detail::suggestion_for(const_cast<ScriptVm*>(&vm), L, message.c_str(), hint, sizeof hint);
    if (has_place(vm, message.c_str())) throw InputError(printable(message + hint));
    throw InputError(printable(vm.display_name + ": " + message + hint));
  }
  throw InputError(printable(vm.display_name) + ": error while loading (error object is a " +
                   luaL_typename(L, -1) + " value)");
}

// Records why a call failed, without allocating on the C++ side.
void record_call_failure(ScriptVm* vm, int status, const char* what) {
  lua_State* L = vm->L;
  if (vm->fault_length > 0) return;  // a tripped limit already said why
  if (status != LUA_OK && lua_type(L, -1) == LUA_TSTRING) {
    // Escaped first, so a NUL in error("...") cannot cut the message short (record_fault
    // escapes the rest; escaping twice changes nothing).
    std::size_t length = 0;
    const char* raw = lua_tolstring(L, -1, &length);
    char message[ScriptVm::kFaultBytes];
    write_printable(std::string_view(raw, length), message, sizeof message);
    // The "did you mean" search of a failed lookup runs here, once, for the reported error.
    char hint[160];
    detail::suggestion_for(vm, L, message, hint, sizeof hint);
    if (has_place(*vm, message)) {
      detail::record_fault(vm, ScriptFault::error, "%s%s", message, hint);
    } else {
      detail::record_fault(vm, ScriptFault::error, "%s: %s%s", vm->display_name.c_str(), message, hint);
    }
    return;
  }
  if (status != LUA_OK) {
    detail::record_fault(vm, ScriptFault::error, "%s: error in %s (error object is a %s value)",
                         vm->display_name.c_str(), what, luaL_typename(L, -1));
    return;
  }
  detail::record_fault(vm, ScriptFault::error, "%s: the call to %s failed", vm->display_name.c_str(),
                       what);
}

void disable(ScriptVm* vm) {
  vm->disabled = true;
  ++vm->fault_count;
  vm->fault_time_s = vm->now_s;
}

// s.<key> = value in the hidden data table. The key exists and is never nil, so this
// only overwrites a slot: it cannot allocate or raise outside a protected call.
void set_state(lua_State* L, int key_slot, double value) {
  lua_pushvalue(L, key_slot);
  lua_pushnumber(L, value);
  lua_rawset(L, detail::kSlotData);
}

// Bit for bit: -0.0 is not 0.0 here, and a NaN is itself.
bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

// Whether s.<key> holds exactly `value`.
bool state_holds(lua_State* L, int key_slot, double value) {
  lua_pushvalue(L, key_slot);
  const bool number = lua_rawget(L, detail::kSlotData) == LUA_TNUMBER;
  const double held = number ? lua_tonumber(L, -1) : 0.0;
  lua_pop(L, 1);
  return number && same_bits(held, value);
}

// Whether force(s) may be called again with s as it is, changing nothing (see
// ScriptInstance::warm): it runs unhooked and only reads, and s holds the input of the
// last call, which succeeded (any failed call disables; last_dt_s > 0 once a call wrote s).
bool can_repeat_last_call(const ScriptVm* vm) {
  return !vm->disabled && vm->unhooked && !vm->script_metamethods && vm->force_reads_only && vm->last_dt_s > 0.0;
}

// Whether a call with `input` would be the last call again: it may repeat, and every value
// it would write into s is already there, bit for bit (t: the last call's, now_s).
template <int N>
bool repeats_last_call(const ScriptVm* vm, const ScriptInputOf<N>& input) {
  lua_State* L = vm->L;
  if (!can_repeat_last_call(vm) || !same_bits(input.dt_s, vm->last_dt_s) || !same_bits(input.t_s, vm->now_s)) {
    return false;
  }
  for (int i = 0; i < N; ++i) {
    if (!state_holds(L, detail::key_slot(detail::position_field(i)), component(input.x_m, i))) return false;
    if (vm->needs_velocity &&
        !state_holds(L, detail::key_slot(detail::velocity_field(i)), component(input.v_m_per_s, i))) {
      return false;
    }
  }
  return !vm->needs_time || state_holds(L, detail::kSlotKeyT, input.t_s);
}

// force(s) from its translation (force_program.hpp) on `input`: true, with the force, when
// it returned what the scene needs (N finite numbers); false otherwise (the VM is then
// the one to ask). Inlined into force_N, as the call path it is (out of line it costs
// the 1-D Lua spring 18 more instructions a tick, callgrind).
template <int N>
[[gnu::always_inline]] inline bool translated_force(ScriptVm* vm, const ScriptInputOf<N>& input, Axes<N>* force_N) {
  if constexpr (N > detail::ForceProgram::kMaxResults) {
    return false;  // not translated (see create)
  }
  detail::ForceProgram& program = *vm->force_program;
  for (int i = 0; i < N; ++i) {
    program.set_field(detail::position_field(i), component(input.x_m, i));
    program.set_field(detail::velocity_field(i), component(input.v_m_per_s, i));
  }
  program.set_field(detail::kFieldT, input.t_s);
  program.set_field(detail::kFieldDt, input.dt_s);
  double results[detail::ForceProgram::kMaxResults];
  const int count = program.run(results);
  if constexpr (N == 1) {
    // One value is kept, as the VM's call keeps one.
    if (count < 1 || !std::isfinite(results[0])) return false;
    *force_N = results[0];
  } else if constexpr (N <= detail::ForceProgram::kMaxResults) {
    if (count != N) return false;
    for (int i = 0; i < N; ++i) {
      if (!std::isfinite(results[i])) return false;
      (*force_N)[i] = results[i];
    }
  }
  return true;
}

}  // namespace

ScriptInstance::ScriptInstance(std::unique_ptr<detail::ScriptVm> vm) : vm_(std::move(vm)) {}

ScriptInstance::~ScriptInstance() {
  if (vm_ && vm_->L) lua_close(vm_->L);
}

std::unique_ptr<ScriptInstance> ScriptInstance::create(const ScriptProgram& program) {
  auto owned = std::make_unique<ScriptVm>();
  ScriptVm* vm = owned.get();
  vm->display_name = program.display_name;
  vm->short_source = short_source_of(program.display_name);
  vm->limits = program.limits;
  vm->axes = program.axes;
  vm->backstop_s = call_time_backstop_s(program.limits);
  vm->source = &program.source;
  vm->params_override = program.params_override.get();
  vm->error_context = program.error_context;
  vm->pointer_prefix = program.pointer_prefix;
  vm->log.configure(program.limits.log_messages_per_s, program.limits.log_burst);

  // The state, with our allocator; the instance owns it from here (closed on any throw).
  lua_State* L = lua_newstate(detail::capped_alloc, vm);
  if (L == nullptr) {
    throw InputError(program.display_name + ": cannot create a Lua state within the memory limit (" +
                     std::to_string(program.limits.memory_bytes) + " bytes)");
  }
  vm->L = L;
  *static_cast<ScriptVm**>(lua_getextraspace(L)) = vm;
  std::unique_ptr<ScriptInstance> instance(new ScriptInstance(std::move(owned)));

  // The collector only runs when collect_garbage() says so.
  lua_gc(L, LUA_GCSTOP);
  lua_gc(L, LUA_GCINC, 0, 0, kGcStepSizeLog2);

  // Load: sandbox, chunk (text only, named "@display_name" so messages read
  // "scripts/bumps.lua:12: ..."), top-level code, then the checks. One budget and one
  // deadline for all (checked by the count hook, charged functions and the allocator,
  // which is all that runs while Lua compiles).
  vm->load_deadline = std::chrono::steady_clock::now() +
                      std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                          std::chrono::duration<double>(program.limits.load_time_s));
  detail::begin_call(vm, program.limits.instructions_at_load, static_cast<std::size_t>(-1));
  lua_pushcfunction(L, detail::open_sandbox);
  if (lua_pcall(L, 0, 0, 0) != LUA_OK) throw_load_failure(*vm, L);
  const std::string chunk_name = "@" + program.display_name;
  if (luaL_loadbufferx(L, program.source.data(), program.source.size(), chunk_name.c_str(), "t") !=
      LUA_OK) {
    throw_load_failure(*vm, L);
  }
  const int status = lua_pcall(L, 0, 0, 0);
  // A load error may have been caught by a pcall in the script: it still fails the load.
  if (status != LUA_OK || vm->tripped || !vm->load_error.empty()) throw_load_failure(*vm, L);
  lua_pushcfunction(L, detail::finish_load);
  if (lua_pcall(L, 0, detail::kSlotCount, 0) != LUA_OK || vm->tripped) throw_load_failure(*vm, L);
  // The warm-up function: the sandbox's own code, not the script's (nothing it touches is
  // the script's but the fields of s, which it only reads).
  static constexpr char kWarmSource[] = "local s = ... return s.x";
  if (luaL_loadbufferx(L, kWarmSource, sizeof kWarmSource - 1, "=(warm)", "t") == LUA_OK) {
    vm->warm_ref = luaL_ref(L, LUA_REGISTRYINDEX);
  } else {
    lua_pop(L, 1);
  }
  detail::end_call(vm);

  // Running from here on: new globals are errors. Start with a clean heap.
  const detail::FunctionCode force_code = detail::read_function_code(L, detail::kSlotForce);
  vm->force_straight_line = force_code.straight_line_length;
  vm->force_calls = force_code.straight_line_length == 0 || force_code.calls;
  vm->force_reads_only = force_code.reads_only;
  // A force that only reads fields of `s` gets the data table itself (no proxy hop): it
  // cannot write it or let it escape, and an unknown field is still an error there.
  vm->state_slot = force_code.first_parameter_read_by_field_only ? detail::kSlotData : detail::kSlotState;
  // A force that would run unhooked, reads s by field only and is arithmetic on numbers
  // runs from its translation (force_program.hpp).
  if (program.limits.translate_force && vm->axes <= detail::ForceProgram::kMaxResults &&
      force_code.first_parameter_read_by_field_only && !vm->force_calls &&
      force_code.straight_line_length > 0 && force_code.straight_line_length <= detail::kMaxStraightLine &&
      force_code.straight_line_length < vm->limits.instructions_per_call) {
    detail::FunctionChunk chunk;
    if (detail::read_function_chunk(L, detail::kSlotForce, &chunk)) {
      std::array<const char*, detail::kFieldCount> fields{};
      for (int f = 0; f < detail::kFieldCount; ++f) {
        const bool present = (f != detail::kFieldT || vm->needs_time) && (!detail::is_velocity_field(f) || vm->needs_velocity);
        fields[static_cast<std::size_t>(f)] = present ? detail::state_field_name(f, vm->axes) : nullptr;
      }
      vm->force_program = detail::ForceProgram::translate(chunk, fields, L, detail::kSlotForce);
    }
  }
  vm->force_translated = vm->force_program.has_value() && !vm->script_metamethods;
  vm->phase = detail::Phase::running;
  vm->source = nullptr;
  vm->params_override = nullptr;
  lua_gc(L, LUA_GCCOLLECT);
  vm->bytes_after_cycle = vm->bytes;
  return instance;
}

namespace {

// "nan", "-inf", or the number as %.17g, for messages about a return value.
void describe_number(double value, char* out, std::size_t size) {
  if (std::isnan(value)) {
    std::snprintf(out, size, "nan");
  } else if (std::isinf(value)) {
    std::snprintf(out, size, "%s", value > 0 ? "inf" : "-inf");
  } else {
    std::snprintf(out, size, "%.17g", value);
  }
}

inline constexpr const char* kCountWords[] = {"no", "one", "two", "three", "four"};
static_assert(kMaxAxes < static_cast<int>(std::size(kCountWords)), "every count of results has a word");

// "fx, fy": the forces a scene of `axes` axes asks force(s) for.
void write_force_names(int axes, char* out, std::size_t size) {
  std::size_t used = 0;
  out[0] = '\0';
  for (int i = 0; i < axes; ++i) detail::append_text(out, size, &used, "%sf%s", i == 0 ? "" : ", ", kAxisNames[i]);
}

// Why the `results` values force(s) returned (on the stack's top) are not the N finite
// numbers of a scene of N >= 2 axes: the fault, recorded.
void record_bad_results(ScriptVm* vm, int results, int axes) {
  lua_State* L = vm->L;
  const char* name = vm->short_source.c_str();
  char forces[32];
  write_force_names(axes, forces, sizeof forces);
  const char* expected = kCountWords[axes];
  bool numbers = true;
  for (int k = 0; k < results; ++k) numbers = numbers && lua_type(L, -results + k) == LUA_TNUMBER;
  char got[192];
  std::size_t used = 0;
  got[0] = '\0';
  if (results == axes && numbers) {
    // The right count, but a value that is not finite: each value as it was.
    for (int k = 0; k < results; ++k) {
      char number[32];
      describe_number(lua_tonumber(L, -results + k), number, sizeof number);
      detail::append_text(got, sizeof got, &used, "%s%s", k == 0 ? "" : ", ", number);
    }
    detail::record_fault(vm, ScriptFault::bad_return, "%s:%d: force(s) returned %s, expected %s finite numbers %s (N)",
                         name, vm->force_line, got, expected, forces);
  } else if (results == axes) {
    // The right count, not all numbers: "a number and a nil".
    for (int k = 0; k < results; ++k) {
      const char* joint = k == 0 ? "" : k + 1 == results ? " and " : ", ";
      detail::append_text(got, sizeof got, &used, "%sa %s", joint, luaL_typename(L, -results + k));
    }
    detail::record_fault(vm, ScriptFault::bad_return, "%s:%d: force(s) returned %s, expected %s finite numbers %s (N)",
                         name, vm->force_line, got, expected, forces);
  } else if (numbers && results >= 1 && detail::scene_axes_supported(results)) {
    // As many numbers as a scene of another number of axes asks for.
    detail::record_fault(vm, ScriptFault::bad_return,
                         "%s:%d: force(s) returned %s number%s, expected %s, %s (N): this is a %d-D scene, and a "
                         "%d-D script returns %s (docs/reference/lua.md, \"Scripts in 2-D\")",
                         name, vm->force_line, kCountWords[results], results == 1 ? "" : "s", expected, forces, axes,
                         results, kCountWords[results]);
  } else {
    detail::record_fault(vm, ScriptFault::bad_return, "%s:%d: force(s) returned %d value%s, expected %s finite numbers %s (N)",
                         name, vm->force_line, results, results == 1 ? "" : "s", expected, forces);
  }
}

}  // namespace

template <int N>
Axes<N> ScriptInstance::force_N(const ScriptInputOf<N>& input) noexcept {
  ScriptVm* vm = vm_.get();
  if (vm->disabled || vm->dry_run) [[unlikely]] {
    if (!vm->dry_run) {
      ++vm->skipped_calls;
      return {};
    }
    // The dry tick. A translated force has no side effects: it runs on any input (a
    // result that is not plainly good is 0 N here; the VM is not asked).
    if (vm->force_translated && !vm->disabled) {
      ++vm->dry_calls;
      Axes<N> force{};
      return translated_force(vm, input, &force) ? force : Axes<N>{};
    }
    // Else the last call again, through this code, only when that changes nothing.
    if (!repeats_last_call(vm, input)) {
      warm();
      return {};
    }
    ++vm->dry_calls;
  }
  lua_State* L = vm->L;
  vm->now_s = input.t_s;
  if (vm->force_translated) {
    Axes<N> force{};
    if (translated_force(vm, input, &force)) return force;
    vm->last_dt_s = std::numeric_limits<double>::quiet_NaN();  // the VM's s was not kept up to date
  }
  detail::begin_call(vm, vm->limits.instructions_per_call, vm->limits.allocation_bytes_per_call,
                     vm->force_straight_line, vm->force_calls);

  // s, then force(s) in protected mode.
  for (int i = 0; i < N; ++i) set_state(L, detail::key_slot(detail::position_field(i)), component(input.x_m, i));
  if (vm->needs_velocity) {
    for (int i = 0; i < N; ++i) set_state(L, detail::key_slot(detail::velocity_field(i)), component(input.v_m_per_s, i));
  }
  if (vm->needs_time) set_state(L, detail::kSlotKeyT, input.t_s);
  if (input.dt_s != vm->last_dt_s) {
    set_state(L, detail::kSlotKeyDt, input.dt_s);
    vm->last_dt_s = input.dt_s;
  }
  lua_pushvalue(L, detail::kSlotForce);
  lua_pushvalue(L, vm->state_slot);
  // In 1-D the first result is kept (the load check counts them); with more axes every
  // result, to count them. A tripped limit fails the call even if the script caught the
  // error and returned.
  const int status = lua_pcall(L, 1, N == 1 ? 1 : LUA_MULTRET, 0);
  detail::end_call(vm);
  if (status == LUA_OK && !vm->tripped) {
    if constexpr (N == 1) {
      if (lua_type(L, -1) == LUA_TNUMBER) {
        const double force = lua_tonumber(L, -1);
        lua_settop(L, detail::kSlotCount);
        if (std::isfinite(force)) return force;
        detail::record_fault(vm, ScriptFault::bad_return,
                             "%s:%d: force(s) returned %s, expected a finite number (N)",
                             vm->short_source.c_str(), vm->force_line,
                             std::isnan(force) ? "nan" : (force > 0 ? "inf" : "-inf"));
      } else {
        detail::record_fault(vm, ScriptFault::bad_return,
                             "%s:%d: force(s) returned %s, expected a finite number (N)",
                             vm->short_source.c_str(), vm->force_line, luaL_typename(L, -1));
      }
    } else {
      const int results = lua_gettop(L) - detail::kSlotCount;
      if (results == N) {
        Axes<N> force{};
        bool good = true;
        for (int i = 0; i < N; ++i) {
          good = good && lua_type(L, -N + i) == LUA_TNUMBER;
          force[i] = good ? lua_tonumber(L, -N + i) : 0.0;
          good = good && std::isfinite(force[i]);
        }
        if (good) {
          lua_settop(L, detail::kSlotCount);
          return force;
        }
      }
      record_bad_results(vm, results, N);
    }
  } else {
    record_call_failure(vm, status, "force(s)");
  }
  lua_settop(L, detail::kSlotCount);
  disable(vm);
  return {};
}

#define HAPSCENE_SCRIPT_FORCE(N) template Axes<N> ScriptInstance::force_N<N>(const ScriptInputOf<N>&) noexcept;
HAPSCENE_FOR_EACH_AXES(HAPSCENE_SCRIPT_FORCE)
#undef HAPSCENE_SCRIPT_FORCE

int ScriptInstance::check_force_results() noexcept {
  ScriptVm* vm = vm_.get();
  if (vm->disabled) return -1;
  lua_State* L = vm->L;
  vm->now_s = 0.0;
  detail::begin_call(vm, vm->limits.instructions_per_call, vm->limits.allocation_bytes_per_call,
                     vm->force_straight_line, vm->force_calls);
  for (int i = 0; i < vm->axes; ++i) set_state(L, detail::key_slot(detail::position_field(i)), 0.0);
  lua_pushvalue(L, detail::kSlotForce);
  lua_pushvalue(L, vm->state_slot);
  const int status = lua_pcall(L, 1, LUA_MULTRET, 0);
  detail::end_call(vm);
  if (status != LUA_OK || vm->tripped) {
    record_call_failure(vm, status, "force(s)");
    lua_settop(L, detail::kSlotCount);
    disable(vm);
    return -1;
  }
  const int results = lua_gettop(L) - detail::kSlotCount;
  lua_settop(L, detail::kSlotCount);
  return results;
}

void ScriptInstance::reset() noexcept {
  ScriptVm* vm = vm_.get();
  lua_State* L = vm->L;
  if (vm->disabled || lua_isnil(L, detail::kSlotReset)) return;
  detail::begin_call(vm, vm->limits.instructions_per_call, vm->limits.allocation_bytes_per_call);
  lua_pushvalue(L, detail::kSlotReset);
  const int status = lua_pcall(L, 0, 0, 0);
  detail::end_call(vm);
  if (status != LUA_OK || vm->tripped) {
    record_call_failure(vm, status, "reset()");
    disable(vm);
  }
  lua_settop(L, detail::kSlotCount);
  // reset() may have changed force's upvalues, or set a metamethod: the translation reads
  // them again, or stops for good.
  if (vm->force_translated &&
      (vm->script_metamethods || !vm->force_program->read_upvalues(L, detail::kSlotForce))) {
    vm->force_translated = false;
    vm->last_dt_s = std::numeric_limits<double>::quiet_NaN();
  }
}

void ScriptInstance::collect_garbage(int max_steps) noexcept {
  ScriptVm* vm = vm_.get();
  // Nothing to do while the heap is within a small slack of its size after the last
  // cycle: a non-allocating script never pays for the collector.
  const std::size_t slack = std::min<std::size_t>(vm->limits.memory_bytes / 16, 64u << 10);
  if (!vm->gc_cycle_in_progress && vm->bytes <= vm->bytes_after_cycle + slack) return;
  for (int step = 0; step < max_steps; ++step) {
    if (lua_gc(vm->L, LUA_GCSTEP, 0) != 0) {
      vm->gc_cycle_in_progress = false;
      vm->bytes_after_cycle = vm->bytes;
      return;
    }
    vm->gc_cycle_in_progress = true;
  }
}

void ScriptInstance::warm() noexcept {
  ScriptVm* vm = vm_.get();
  // A translated force is pure: running it (on the last call's s) warms its code and data.
  if (vm->force_translated && !vm->disabled) {
    double results[detail::ForceProgram::kMaxResults];
    vm->force_program->run(results);
    asm volatile("" : : "m"(results));
    ++vm->dry_calls;
    return;
  }
  // Only between unhooked calls: a hook's count carries over from call to call, so code run
  // under it would change when the next call's budget runs out.
  if (vm->disabled || !vm->unhooked) return;
  lua_State* L = vm->L;
  if (can_repeat_last_call(vm)) {
    // A dry call: force(s) again, with s as the last call, which succeeded, left it. force
    // runs unhooked and only reads (no write of an upvalue, a global or a table, nothing
    // made, no call; no metamethod of the script's and no weak table in reach), so it
    // does exactly what the last call did and leaves the state as that call left it. Its
    // results are dropped. Before it, s.x is written with its own value: the next call's
    // write path, with no change.
    detail::begin_call(vm, vm->limits.instructions_per_call, vm->limits.allocation_bytes_per_call,
                       vm->force_straight_line, vm->force_calls);
    lua_pushvalue(L, detail::kSlotKeyX);
    lua_pushvalue(L, detail::kSlotKeyX);
    lua_rawget(L, detail::kSlotData);
    lua_rawset(L, detail::kSlotData);
    lua_pushvalue(L, detail::kSlotForce);
    lua_pushvalue(L, vm->state_slot);
    lua_pcall(L, 1, LUA_MULTRET, 0);
    detail::end_call(vm);
    lua_settop(L, detail::kSlotCount);
    ++vm->dry_calls;
    return;
  }
  // Otherwise the call path alone: a function of the sandbox's own that reads s.x.
  if (vm->warm_ref == LUA_NOREF) return;
  lua_rawgeti(L, LUA_REGISTRYINDEX, vm->warm_ref);
  lua_pushvalue(L, vm->state_slot);
  lua_pcall(L, 1, 1, 0);  // s.x exists: it cannot fail; its result is dropped either way
  lua_settop(L, detail::kSlotCount);
}

void ScriptInstance::begin_dry_run() noexcept { vm_->dry_run = true; }
void ScriptInstance::end_dry_run() noexcept { vm_->dry_run = false; }
std::uint64_t ScriptInstance::dry_calls() const noexcept { return vm_->dry_calls; }

bool ScriptInstance::disabled() const noexcept { return vm_->disabled; }

std::int64_t ScriptInstance::force_straight_line_instructions() const noexcept {
  return vm_->force_straight_line;
}

bool ScriptInstance::force_reads_state_directly() const noexcept { return vm_->state_slot == detail::kSlotData; }

bool ScriptInstance::force_translated() const noexcept { return vm_->force_translated; }

bool ScriptInstance::force_runs_without_hooks() const noexcept {
  return vm_->force_straight_line > 0 && !vm_->force_calls && !vm_->script_metamethods;
}

std::string_view ScriptInstance::fault_message() const noexcept {
  return std::string_view(vm_->fault, vm_->fault_length);
}

std::uint64_t ScriptInstance::fault_count() const noexcept { return vm_->fault_count; }

ScriptFault ScriptInstance::fault() const noexcept {
  return vm_->disabled ? vm_->fault_kind : ScriptFault::none;
}

std::uint64_t ScriptInstance::skipped_calls() const noexcept { return vm_->skipped_calls; }

double ScriptInstance::fault_time_s() const noexcept { return vm_->fault_time_s; }

void ScriptInstance::drain_log(std::vector<std::string>* out) {
  vm_->log.drain(vm_->display_name, out);
}

std::size_t ScriptInstance::memory_bytes() const noexcept { return vm_->bytes; }

std::uint64_t ScriptInstance::allocation_count() const noexcept { return vm_->allocations; }

}  // namespace hapscene
