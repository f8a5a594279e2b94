// The instruction budget. A count hook on every thread subtracts the instructions run
// since it last fired; at the deadline the state "trips": the hook is switched to fire on
// every instruction and raises each time, so a script that catches the error with pcall
// (or in a coroutine) fails again on its next instruction, until the call returns.
//
// A count hook makes Lua check every instruction, which costs more than a short force()
// itself. So a function that cannot loop (bytecode.hpp) runs under a call hook instead:
// its own code is charged its length up front, and the first Lua function it calls
// (directly, through a metamethod, pcall, a C function or a coroutine) switches every
// thread to counting for the rest of the call.
#include <cstdarg>
#include <cstdio>
#include <ctime>

#include "engine/base/format.hpp"
#include "engine/lua/script_vm.hpp"

namespace hapscene::detail {
namespace {

// The error value raised for a tripped limit; its address is unique and pushing it
// allocates nothing. The message is in ScriptVm::fault.
const char kTrippedError = 0;

using Clock = std::chrono::steady_clock;

// A call that has run this long is no longer ordinary: its CPU time is measured from here.
constexpr auto kSlowCall = std::chrono::milliseconds(1);

double thread_cpu_s() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

Clock::duration to_duration(double seconds) {
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
}

const char* budget_phrase(const ScriptVm* vm) {
  return vm->phase == Phase::loading ? "instructions while loading" : "instructions per call";
}

}  // namespace

void begin_call(ScriptVm* vm, std::int64_t instructions, std::size_t allocation_limit_bytes,
                std::int64_t straight_line_instructions, bool straight_line_calls) {
  vm->budget_instructions = instructions;
  vm->remaining_instructions = instructions;
  if (straight_line_instructions > 0 && straight_line_instructions < instructions &&
      straight_line_instructions <= kMaxStraightLine && !vm->tripped) {
    // The function's own code runs uncounted, charged its length up front.
    vm->remaining_instructions -= straight_line_instructions;
    vm->entered_function = false;
    if (!straight_line_calls && !vm->script_metamethods) {
      // Sealed: it calls nothing, and no operator or field read can run script code (the
      // metamethods in reach are the sandbox's own C guards), so no hook is needed: its
      // length bounds it. (Lua's call hook alone costs about as much as a short force.)
      if (!vm->unhooked) {
        vm->unhooked = true;
        vm->hook_on_calls = false;
        vm->hook_period = 0;
        lua_sethook(vm->L, nullptr, 0, 0);
      }
    } else if (!vm->hook_on_calls) {
      // The call hook switches to counting as soon as it calls a Lua function.
      vm->unhooked = false;
      vm->hook_on_calls = true;
      vm->hook_period = 0;
      lua_sethook(vm->L, call_hook, LUA_MASKCALL, 0);
    }
  } else {
    // The hook is installed once per phase; between calls its count carries over, so a
    // call's budget is exact to within one hook period.
    const std::int64_t period = instructions < kHookPeriod ? instructions : kHookPeriod;
    if (period != vm->hook_period || vm->tripped) start_counting(vm, vm->L, period);
  }
  vm->tripped = false;
  vm->clock_started = false;
  vm->slow = false;
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

void start_counting(ScriptVm* vm, lua_State* L, std::int64_t period) {
  vm->hook_on_calls = false;
  vm->unhooked = false;
  vm->hook_period = period;
  lua_sethook(L, count_hook, LUA_MASKCOUNT, static_cast<int>(period));
  if (L != vm->L) lua_sethook(vm->L, count_hook, LUA_MASKCOUNT, static_cast<int>(period));
}

void call_hook(lua_State* L, lua_Debug* ar) {
  ScriptVm* vm = vm_of(L);
  // The first call of a call is the straight-line function itself.
  if (!vm->entered_function) {
    vm->entered_function = true;
    return;
  }
  // C functions are bounded (the costly ones charge their work); they may call Lua
  // functions, which come through here.
  lua_getinfo(L, "f", ar);
  const bool c_function = lua_iscfunction(L, -1) != 0;
  lua_pop(L, 1);
  if (c_function) return;
  // A Lua function may loop: count from its first instruction on, on this thread and
  // the main one, until the call ends.
  const std::int64_t budget = vm->budget_instructions;
  start_counting(vm, L, budget < kHookPeriod ? budget : kHookPeriod);
}

void end_call(ScriptVm* vm) { vm->in_call = false; }

void count_hook(lua_State* L, lua_Debug* ar) {
  ScriptVm* vm = vm_of(L);
  if (!vm->tripped) {
    // This thread's own period: a coroutine keeps the hook it had when it was counting.
    vm->remaining_instructions -= lua_gethookcount(L);
    const bool over_budget = vm->remaining_instructions <= 0;
    if (over_budget) {
      // Level 0 inside a hook is the function being run.
      lua_getinfo(L, "Sl", ar);
      record_fault(vm, ScriptFault::instruction_budget, "%s:%d: instruction budget exceeded (%lld %s)",
                   ar->short_src, ar->currentline, static_cast<long long>(vm->budget_instructions),
                   budget_phrase(vm));
    } else {
      if (!time_exceeded(vm, L, 0)) return;
    }
    trip(vm, L);
  }
  raise_tripped(L);
}

bool time_exceeded(ScriptVm* vm, lua_State* L, int level) {
  const Clock::time_point now = Clock::now();
  char where[160];
  const auto locate = [&] { describe_position(L, level, vm, where, sizeof where); };
  // The call's clock starts at its first checkpoint (reading it on entry would cost every
  // call). The hook period never depends on time, so the instruction count stays exact
  // and machine-independent.
  const bool first_check = !vm->clock_started;
  if (first_check) {
    vm->clock_started = true;
    vm->clock_start = now;
  }

  if (vm->phase == Phase::loading) {
    if (now <= vm->load_deadline) return false;
    locate();
    record_fault(vm, ScriptFault::time_limit,
                 "%s: load time limit exceeded (%g s to load the script)", where,
                 vm->limits.load_time_s);
    return true;
  }
  if (vm->check_clock && now > vm->deadline) {
    locate();
    record_fault(vm, ScriptFault::time_limit, "%s: time limit exceeded (%g ms per call)", where,
                 vm->limits.wall_time_per_call_s * 1e3);
    return true;
  }

  // The backstop, on CPU time.
  if (!vm->slow) {
    if (first_check || now - vm->clock_start < kSlowCall) return false;
    // Measure CPU time from here on (reading it is a system call: only in long calls).
    vm->slow = true;
    vm->wall_before_slow = now - vm->clock_start;
    vm->cpu_at_slow_s = thread_cpu_s();
    vm->next_cpu_check = vm->clock_start + to_duration(vm->backstop_s);
    return false;
  }
  if (now < vm->next_cpu_check) return false;
  // Wall time says the backstop is reached; CPU time decides (preemption is not the
  // script's doing).
  const double used_s = std::chrono::duration<double>(vm->wall_before_slow).count() +
                        (thread_cpu_s() - vm->cpu_at_slow_s);
  if (used_s < vm->backstop_s) {
    vm->next_cpu_check = now + to_duration(vm->backstop_s - used_s);
    return false;
  }
  locate();
  record_fault(vm, ScriptFault::time_limit,
               "%s: time backstop exceeded (%g ms of CPU time per call; instructions that cost "
               "far more than usual, see docs/reference/lua.md)", where, vm->backstop_s * 1e3);
  return true;
}

void charge(lua_State* L, std::int64_t instructions) {
  ScriptVm* vm = vm_of(L);
  if (vm->tripped) raise_tripped(L);
  vm->remaining_instructions -= instructions;
  if (vm->remaining_instructions > 0) {
    if (!time_exceeded(vm, L, 1)) return;
    trip(vm, L);
    raise_tripped(L);
  }
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
  char raw[ScriptVm::kFaultBytes];
  const int n = std::vsnprintf(raw, sizeof raw, format, args);
  va_end(args);
  if (n < 0) return;
  // The message carries the script's own text (error("..."), a path): printable, so it
  // can neither forge output lines nor be cut short by a NUL (engine/base/format.hpp).
  const std::size_t raw_length = static_cast<std::size_t>(n) < sizeof raw ? static_cast<std::size_t>(n) : sizeof raw - 1;
  vm->fault_length = write_printable(std::string_view(raw, raw_length), vm->fault, ScriptVm::kFaultBytes);
  if (vm->fault_length == 0) vm->fault_length = write_printable("script fault", vm->fault, ScriptVm::kFaultBytes);
}

void trip(ScriptVm* vm, lua_State* L) {
  vm->tripped = true;
  start_counting(vm, L, 1);
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

namespace hapscene {

double call_time_backstop_s(const ScriptLimits& limits) {
  constexpr double kPerInstruction_s = 1e-6;
  constexpr double kFloor_s = 0.02;
  const double backstop_s = static_cast<double>(limits.instructions_per_call) * kPerInstruction_s;
  return backstop_s > kFloor_s ? backstop_s : kFloor_s;
}

}  // namespace hapscene
