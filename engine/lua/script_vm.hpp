#pragma once
// Internal: the state one sandboxed lua_State shares with the C functions that guard it
// (allocator, count hook, sandbox library functions). A pointer to it lives in the
// state's extra space, so every thread (coroutine) of the state finds it in O(1).
//
// Rule for every lua_CFunction and hook in engine/lua: a Lua error is a longjmp, so no
// C++ object with a destructor may be alive where one can be raised, and no C++
// exception may leave the function. C++ work that allocates or throws runs in noexcept
// helpers that raise no Lua error and leave their results in this struct.
#include <lua.hpp>

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "engine/lua/force_program.hpp"
#include "engine/lua/log_queue.hpp"
#include "engine/lua/script.hpp"
#include "engine/lua/state_fields.hpp"

namespace hapscene::detail {

// Fixed slots at the bottom of the main thread's stack, set once after loading, so each
// call pushes its arguments without a lookup.
inline constexpr int kSlotForce = 1;  // the script's force function
inline constexpr int kSlotReset = 2;  // reset function, or nil
inline constexpr int kSlotState = 3;  // `s`: an empty read-only proxy table
inline constexpr int kSlotData = 4;   // the hidden table `s` reads from
// Then the name of each field of s as a Lua string, in the order of state_fields.hpp
// ("t", "dt", "x", "y", ..., "v" or "vx", "vy", ...; "" where the scene has no such field).
constexpr int key_slot(int field) noexcept { return 5 + field; }
inline constexpr int kSlotKeyT = key_slot(kFieldT);
inline constexpr int kSlotKeyDt = key_slot(kFieldDt);
inline constexpr int kSlotKeyX = key_slot(position_field(0));
inline constexpr int kSlotCount = key_slot(kFieldCount - 1);

// The hook fires every this many instructions (fewer when the budget is smaller).
inline constexpr std::int64_t kHookPeriod = 128;
// Longest force() that runs uncounted (see begin_call): no time check runs inside it, so
// its length times the costliest instruction bounds the call.
inline constexpr std::int64_t kMaxStraightLine = 256;

enum class Phase { loading, running };

// What a failed lookup left for the suggestion search (see suggestions.cpp).
struct PendingSuggestion {
  enum class Kind { none, global, params, state, library };
  Kind kind{Kind::none};
  char message[256]{};  // the error as raised, with its place
  char name[64]{};      // the name looked up (suggestions are for names up to 48 bytes)
  char library[16]{};   // for Kind::library
};

struct ScriptVm {
  // Set at creation.
  lua_State* L{};
  std::string display_name;  // "scripts/bumps.lua"
  std::string short_source;  // what Lua prints for the chunk (same unless very long)
  ScriptLimits limits;
  Phase phase{Phase::loading};
  bool needs_velocity{true};
  bool needs_time{true};
  std::vector<ScriptShape> shapes;  // the `shapes` global, checked (script_shapes.cpp)
  int axes{1};       // of the scene: s has a position and a velocity per axis, force returns axes numbers
  int force_line{};  // line where force is defined, for messages about its return value
  std::int64_t force_straight_line{};  // force's length when it cannot loop, else 0
  bool force_calls{true};  // force's own code has a call instruction (see bytecode.hpp)
  bool force_reads_only{};  // force's own code only reads and computes (FunctionCode::reads_only)
  bool dry_run{};           // between begin_dry_run() and end_dry_run() (ScriptInstance)
  std::uint64_t dry_calls{};  // force calls made again by warm() or a dry run
  // What force(s) gets as `s`: the read-only proxy (kSlotState), or the data table itself
  // (kSlotData) when force's code only reads constant fields of s (see bytecode.hpp).
  int state_slot{kSlotState};
  // A metatable the script set holds a function (sandbox_setmetatable): an operator or a
  // field read may then run script code, or a C function that calls it, without a call
  // instruction. Never cleared: metatables are frozen copies, and stay.
  bool script_metamethods{};
  // force translated to run without the VM (force_program.hpp), and whether it may run:
  // set after load, re-checked after every reset(); the VM answers whenever it may not.
  std::optional<ForceProgram> force_program;
  bool force_translated{};

  // Instruction budget of the current call (see budget.cpp).
  std::int64_t remaining_instructions{};
  std::int64_t budget_instructions{};
  std::int64_t hook_period{0};  // of the count hook; 0: not counting
  bool hook_on_calls{};         // the call hook is installed instead (see begin_call)
  bool unhooked{};              // no hook at all: a sealed straight-line call (see begin_call)
  int warm_ref{LUA_NOREF};      // registry reference of the warm-up function (ScriptInstance::warm)
  bool entered_function{};      // the call hook has seen the called function's own call
  bool check_clock{};
  std::chrono::steady_clock::time_point deadline{};  // of wall_time_per_call_s
  // Time backstop (see check_time in budget.cpp). Loading: a wall-clock deadline.
  // Running: the call's clock starts at its first checkpoint; past kSlowCall the CPU time
  // is read, and the backstop is confirmed on CPU time before it trips.
  std::chrono::steady_clock::time_point load_deadline{};
  double backstop_s{};         // CPU seconds per call (call_time_backstop_s, set at creation)
  bool clock_started{};
  bool slow{};                 // the call has run for over kSlowCall
  std::chrono::steady_clock::time_point clock_start{};
  std::chrono::steady_clock::time_point next_cpu_check{};
  double cpu_at_slow_s{};
  std::chrono::steady_clock::duration wall_before_slow{};
  unsigned allocations_since_check{};
  bool tripped{};  // a limit was exceeded: every instruction raises until the call returns

  // Memory accounting (see allocator.cpp).
  std::size_t bytes{};              // live bytes, as Lua reports them
  std::size_t call_bytes{};         // bytes allocated during the current call
  std::size_t call_limit_bytes{};   // per-call allocation limit of the current call
  bool in_call{};
  std::uint64_t allocations{};      // growing allocations since creation
  const void* retry_block{};        // a refused request Lua may retry after an emergency GC
  std::size_t retry_size{};
  bool awaiting_retry{};

  // Fault state: the first fault wins; the message is kept in a fixed buffer so that
  // recording it inside the tick does not allocate.
  static constexpr std::size_t kFaultBytes = 400;
  char fault[kFaultBytes]{};
  std::size_t fault_length{};
  ScriptFault fault_kind{ScriptFault::none};
  bool disabled{};
  std::uint64_t fault_count{};
  std::uint64_t skipped_calls{};
  double fault_time_s{};
  double now_s{};  // s.t of the current call, for log() and fault_time_s
  // s.dt as last written (it rarely changes, so it is written on change). 0 until the
  // first force call writes s (s.dt starts at 0 and a tick's dt is positive): warm()
  // reads "> 0 and not disabled" as "s holds the input of a force call that succeeded".
  double last_dt_s{};

  // Garbage collection outside the calls.
  bool gc_cycle_in_progress{};
  std::size_t bytes_after_cycle{};

  // Loading: parameter resolution (see params.hpp) runs when the chunk assigns `params`.
  const std::string* source{};  // the script text, to find where a param is declared
  const nlohmann::json* params_override{};
  std::string error_context;
  std::string pointer_prefix;
  bool params_assigned{};
  std::vector<ScriptParam> params;
  std::string load_error;  // set by a C function that failed a load check; thrown later

  // The last failed lookup of a guarded table (globals, params, s, a library), whose
  // "did you mean" search is owed: it runs only if this error is the one reported.
  PendingSuggestion suggestion;

  LogQueue log;
  bool log_writing{};  // inside log(), between taking a slot and publishing it
};

// The ScriptVm of any thread of a sandboxed state.
inline ScriptVm* vm_of(lua_State* L) { return *static_cast<ScriptVm**>(lua_getextraspace(L)); }

// Budget (budget.cpp).
// Starts a call with the given instruction budget and allocation limit. With
// `straight_line_instructions` > 0 (the called function cannot loop and is that long, see
// bytecode.hpp) and below the budget, the function's own code runs without the count
// hook, charged its length up front; anything it calls in Lua is counted. When moreover
// its code has no call instruction (`straight_line_calls` false) and no metatable of the
// script holds a function (vm->script_metamethods), nothing it runs can reach script code
// or a C function of the script's choosing: it runs with no hook at all.
void begin_call(ScriptVm* vm, std::int64_t instructions, std::size_t allocation_limit_bytes,
                std::int64_t straight_line_instructions = 0, bool straight_line_calls = true);
void end_call(ScriptVm* vm);
// Installs the count hook, firing every `period` instructions, on `L` and the main thread.
void start_counting(ScriptVm* vm, lua_State* L, std::int64_t period);
// The count hook: subtracts each period from the budget and trips at the deadline.
void count_hook(lua_State* L, lua_Debug* ar);
// The call hook of a straight-line call: starts counting when a Lua function is called.
void call_hook(lua_State* L, lua_Debug* ar);
// Charges a C function's work as `instructions`; raises if the budget runs out or the
// call is past its time limits.
void charge(lua_State* L, std::int64_t instructions);
// Checks the time limits at a checkpoint (hook, charge, allocation while loading):
// records the fault and returns true when one is exceeded. Never raises.
// `L` and `level` locate the script's position for the message (see describe_position).
bool time_exceeded(ScriptVm* vm, lua_State* L, int level);
// Records the first fault message (printf-style, truncated to the buffer).
void record_fault(ScriptVm* vm, ScriptFault kind, const char* format, ...)
    __attribute__((format(printf, 3, 4)));
// Marks the state tripped: the hook now fires on every instruction of `L` and of the main
// thread, and raises each time, so no pcall inside the script can continue past it.
void trip(ScriptVm* vm, lua_State* L);
// Raises the error value used for tripped limits (a light userdata, no allocation).
int raise_tripped(lua_State* L);
// Writes "short_src:line" of the innermost Lua function at or above `level`, or the
// script name when there is none. Does not allocate.
void describe_position(lua_State* L, int level, const ScriptVm* vm, char* out, std::size_t size);

// Allocator (allocator.cpp): the lua_Alloc of every sandboxed state, `ud` is the ScriptVm.
void* capped_alloc(void* ud, void* block, std::size_t old_size, std::size_t new_size);

// Sandbox (sandbox.cpp).
// lua_CFunction: opens the allowed libraries and makes the script's global table.
int open_sandbox(lua_State* L);
// Gives the table at `index` a hidden metatable (getmetatable answers false) whose
// __index and __newindex are the given functions: for strict globals and sealed params.
void set_guard_metatable(lua_State* L, int index, lua_CFunction on_index, lua_CFunction on_newindex);
// Suggestions (suggestions.cpp).
// Makes the registry slot that holds the table of the last failed lookup (so noting one
// never allocates).
void prepare_suggestions(lua_State* L);
// Raises "<place>: <format with name>" after noting the lookup (argument 1 is the table
// looked up) for suggestion_for.
int raise_lookup_error(lua_State* L, PendingSuggestion::Kind kind, const char* library, const char* format,
                       const char* name);
// When `message` is the error of the last failed lookup, searches that table for the
// nearest name and writes the hint (" (did you mean 'stiffness'?)") into `out`; else
// writes "". Runs once, when an error is reported, outside any protected call: one
// traversal of the table and at most 256 edit distances. Never raises or allocates.
void suggestion_for(ScriptVm* vm, lua_State* L, const char* message, char* out, std::size_t size);
// lua_CFunction __index of the library tables (upvalue 1: the library's name).
int library_index(lua_State* L);
// lua_CFunction: after the chunk ran, checks force/reset/needs/params and sets up `s`
// and the stack slots. Failures are stored in vm->load_error.
int finish_load(lua_State* L);
// Stores the first load error (printf-style) in vm->load_error; it is thrown as an
// InputError once the Lua call returns. Never raises.
void set_load_error(ScriptVm* vm, const char* format, ...) __attribute__((format(printf, 2, 3)));
// params (params_table.cpp). lua_CFunction-style __newindex step of the global table for
// `params = { ... }` while loading (stack: env, "params", table): resolves the declared
// defaults with the overrides, writes the SI values back, seals and stores the table.
int assign_params(lua_State* L);
// After the chunk ran: a script without params gets an empty sealed table; one that
// replaced its table after declaring it is refused. Pushes one value; false with
// vm->load_error set.
bool finish_params(lua_State* L, int env, ScriptVm* vm);
// needs and s (state_table.cpp): checks the optional `needs` table (at `index`) into vm
// (false, with vm->load_error set, on a bad one; never raises); pushes the read-only
// proxy `s` and above it the hidden data table it reads through.
bool check_needs(lua_State* L, int index, ScriptVm* vm) noexcept;
void push_state_tables(lua_State* L, const ScriptVm* vm);
// Shapes (script_shapes.cpp): checks the optional `shapes` list (at `index`) and stores
// it in vm->shapes; false, with vm->load_error set, on the first bad entry.
bool check_shapes(lua_State* L, int index, ScriptVm* vm);

}  // namespace hapscene::detail
