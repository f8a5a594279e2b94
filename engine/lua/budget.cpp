// The instruction budget. A count hook on every thread subtracts the instructions run
// since it last fired; at the deadline the state "trips": the hook is switched to fire on
// every instruction and raises each time, so a script that catches the error with pcall
// (or in a coroutine) fails again on its next instruction, until the call returns.
#include <cstdarg>
#include <cstdio>

#include "engine/lua/script_vm.hpp"

namespace hapscene::detail {
namespace {

// The error value raised for a tripped limit; its address is unique and pushing it
// allocates nothing. The message is in ScriptVm::fault.
const char kTrippedError = 0;

bool past_deadline(const ScriptVm* vm) {
  return vm->check_clock && std::chrono::steady_clock::now() > vm->deadline;
}

const char* budget_phrase(const ScriptVm* vm) {
  return vm->phase == Phase::loading ? "instructions while loading" : "instructions per call";
}

}  // namespace

void begin_call(ScriptVm* vm, std::int64_t instructions, std::size_t allocation_limit_bytes) {
  vm->budget_instructions = instructions;
  vm->remaining_instructions = instructions;
  // The hook is installed once per phase; between calls its count carries over, so a
  // call's budget is exact to within one hook period.
  const std::int64_t period = instructions < kHookPeriod ? instructions : kHookPeriod;
  if (period != vm->hook_period || vm->tripped) {
    vm->hook_period = period;
    lua_sethook(vm->L, count_hook, LUA_MASKCOUNT, static_cast<int>(period));
  }
  vm->tripped = false;
  vm->in_call = true;
  vm->call_bytes = 0;
  vm->call_limit_bytes = allocation_limit_bytes;
  vm->log_writing = false;
  vm->check_clock = vm->limits.wall_time_per_call_s > 0.0 && vm->phase == Phase::running;
  if (vm->check_clock) {
    vm->deadline = std::chrono::steady_clock::now() +
                   std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                       std::chrono::duration<double>(vm->limits.wall_time_per_call_s));
  }
}

void end_call(ScriptVm* vm) { vm->in_call = false; }

void count_hook(lua_State* L, lua_Debug* ar) {
  ScriptVm* vm = vm_of(L);
  if (!vm->tripped) {
    vm->remaining_instructions -= vm->hook_period;
    const bool over_budget = vm->remaining_instructions <= 0;
    const bool over_time = !over_budget && past_deadline(vm);
    if (!over_budget && !over_time) return;
    // Level 0 inside a hook is the function being run.
    lua_getinfo(L, "Sl", ar);
    if (over_budget) {
      record_fault(vm, ScriptFault::instruction_budget, "%s:%d: instruction budget exceeded (%lld %s)",
                   ar->short_src,
                   ar->currentline, static_cast<long long>(vm->budget_instructions),
                   budget_phrase(vm));
    } else {
      record_fault(vm, ScriptFault::time_limit, "%s:%d: time limit exceeded (%g ms per call)",
                   ar->short_src,
                   ar->currentline, vm->limits.wall_time_per_call_s * 1e3);
    }
    trip(vm, L);
  }
  raise_tripped(L);
}

void charge(lua_State* L, std::int64_t instructions) {
  ScriptVm* vm = vm_of(L);
  if (vm->tripped) raise_tripped(L);
  vm->remaining_instructions -= instructions;
  if (vm->remaining_instructions > 0) return;
  char where[160];
  describe_position(L, 1, vm, where, sizeof where);
  record_fault(vm, ScriptFault::instruction_budget,
               "%s: instruction budget exceeded (%lld %s; this call was charged %lld)", where,
               static_cast<long long>(vm->budget_instructions), budget_phrase(vm),
               static_cast<long long>(instructions));
  trip(vm, L);
  raise_tripped(L);
}

void record_fault(ScriptVm* vm, ScriptFault kind, const char* format, ...) {
  if (vm->fault_length > 0) return;
  vm->fault_kind = kind;
  std::va_list args;
  va_start(args, format);
  const int n = std::vsnprintf(vm->fault, ScriptVm::kFaultBytes, format, args);
  va_end(args);
  if (n < 0) return;
  vm->fault_length = static_cast<std::size_t>(n) < ScriptVm::kFaultBytes
                         ? static_cast<std::size_t>(n)
                         : ScriptVm::kFaultBytes - 1;
}

void trip(ScriptVm* vm, lua_State* L) {
  vm->tripped = true;
  lua_sethook(L, count_hook, LUA_MASKCOUNT, 1);
  if (L != vm->L) lua_sethook(vm->L, count_hook, LUA_MASKCOUNT, 1);
}

int raise_tripped(lua_State* L) {
  lua_pushlightuserdata(L, const_cast<char*>(&kTrippedError));
  return lua_error(L);
}

void describe_position(lua_State* L, int level, const ScriptVm* vm, char* out, std::size_t size) {
  lua_Debug ar{};
  for (int i = level; i < level + 8 && lua_getstack(L, i, &ar) != 0; ++i) {
    if (lua_getinfo(L, "Sl", &ar) != 0 && ar.currentline > 0) {
      std::snprintf(out, size, "%s:%d", ar.short_src, ar.currentline);
      return;
    }
  }
  std::snprintf(out, size, "%s", vm->short_source.c_str());
}

}  // namespace hapscene::detail
