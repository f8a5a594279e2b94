#pragma once
// Lua script effects. A script is compiled once at load time into an immutable
// ScriptProgram (source, resolved parameters, declared needs, limits); every run creates
// its own ScriptInstance from it, which owns one sandboxed lua_State. So a scene can be
// run twice, reset or hot-reloaded without one run seeing another's script state.
//
// Script API (docs/reference/lua.md has the full text with examples):
//   params = { stiffness = "100 N/m", center = "0 mm" }   -- defaults; JSON overrides them
//   needs = { velocity = false, time = false }             -- optional: what force() reads
//   function force(s) return -params.stiffness * (s.x - params.center) end
//   function reset() end                                    -- optional, run start/restart
//   log(...) / print(...)                                   -- never block the tick
//
// Threads: create(), force_N(), reset() and collect_garbage() are called by one thread
// (the loop; an instance made off the loop may be handed over, e.g. on hot reload);
// drain_log() may be called by one other thread at the same time. The calling thread
// needs at least 512 KiB of stack: Lua allows 200 nested C calls (metamethod recursion),
// which take about 200 KiB before Lua stops them with "C stack overflow".
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "engine/base/axes.hpp"
#include "engine/base/units.hpp"

namespace hapscene {

namespace detail {
struct ScriptVm;
}

// What a script may use. Every limit is enforced, not advisory; exceeding one disables
// the script (force 0 N from then on) with a message naming the limit.
struct ScriptLimits {
  // VM instructions per force() or reset() call, counted by a hook that keeps firing
  // after the deadline so pcall cannot swallow it. Runaway loops stop after about
  // 0.4 ms at this default; the lab spring is charged 10, the texture 19, pong.lua ~95.
  std::int64_t instructions_per_call{100'000};
  // VM instructions for the top-level chunk, run at load time (off the loop), so a
  // script can precompute tables.
  std::int64_t instructions_at_load{10'000'000};
  // Live bytes of the whole Lua state, garbage included. The sandbox itself takes about
  // 21 KiB; a 100 000-entry lookup table about 1.6 MiB.
  std::size_t memory_bytes{4u << 20};
  // Bytes one force() or reset() call may allocate in total. Bounds the work that C
  // functions (which no hook interrupts) can do per call by allocating.
  std::size_t allocation_bytes_per_call{256u << 10};
  // Longest string a script can create. Bounds string comparisons and scans, each of which
  // is one VM instruction however long the string is.
  std::size_t string_bytes{4096};
  // Wall-clock time per force()/reset() call, checked every 128 instructions; 0 = off.
  // Off by default because it makes faults depend on the machine (simulated runs are
  // deterministic); a real-time runner should set it to about one tick period. (A
  // backstop is always on: see call_time_backstop_s.)
  double wall_time_per_call_s{0.0};
  // Wall-clock time for the whole load of one instance (compile, top-level code,
  // checks), always on. A well-behaved load takes milliseconds; this stops a source
  // that is pathological to compile or a top level whose C work the instruction count
  // does not see. Hot reload relies on it: ScriptInstance::create and compile_script
  // return or throw within load_time_s plus the overshoot bound in docs/reference/lua.md.
  double load_time_s{5.0};
  // log()/print(): messages admitted per second of run time (s.t), and the burst.
  double log_messages_per_s{10.0};
  std::size_t log_burst{20};
  // Run a force(s) that is straight-line arithmetic on numbers from a translation of its
  // bytecode instead of the VM (same results to the bit; see ScriptInstance::
  // force_translated). Not read from files: tests and the bench turn it off to compare.
  bool translate_force{true};
};

// The CPU-time backstop of one force()/reset() call: 1 us per budgeted instruction, at
// least 20 ms (100 ms at the default budget). Plain Lua runs 2-10 ns per instruction, so
// a script within its budget never comes near it and simulated runs stay deterministic;
// it stops a call whose instructions are each very costly (hash-colliding tables, long
// __index chains, sparse traversals), which the instruction count cannot see. It is CPU
// time of the calling thread, so being preempted does not count against the script.
double call_time_backstop_s(const ScriptLimits& limits);

// Why a script was disabled.
enum class ScriptFault {
  none,
  error,               // a runtime error (including C stack overflow)
  bad_return,          // force(s) returned something other than a finite number
  instruction_budget,  // instructions_per_call (C functions are charged for their work)
  time_limit,          // wall_time_per_call_s, the call's CPU-time backstop, or load_time_s
  memory_limit,        // memory_bytes, allocation_bytes_per_call or string_bytes
};

// The state handed to force(s) in a scene of N axes, in SI units: per axis a position
// and a velocity (1-D: s.x, s.v; 2-D: s.x, s.y, s.vx, s.vy; engine/lua/state_fields.hpp),
// then s.t and s.dt. The velocity is absent from s when the script declares
// needs.velocity = false, the time when it declares needs.time = false.
template <int N>
struct ScriptInputOf {
  Axes<N> x_m{};        // handle position
  Axes<N> v_m_per_s{};  // velocity
  double t_s{};         // run time
  double dt_s{};        // tick period
};
using ScriptInput = ScriptInputOf<1>;
using PlanarScriptInput = ScriptInputOf<2>;

// One script parameter after defaults and JSON overrides are applied, in SI.
struct ScriptParam {
  enum class Kind { number, boolean, text };
  std::string name;
  Kind kind{Kind::number};
  bool has_unit{};  // the default was a unit string such as "2 mm"
  Quantity quantity{Quantity::dimensionless};  // meaningful when has_unit
  double value_si{};  // Kind::number
  bool flag{};        // Kind::boolean
  std::string text;   // Kind::text
  bool overridden{};  // set from the JSON params
};

// A shape a 2-D script declares in its optional global `shapes` (docs/reference/lua.md,
// "Scripts in 2-D"), in SI: where validate's scenarios press, corner, swipe and release,
// as they do for the built-in shapes. It describes the script; the script still renders
// itself, and nothing checks that it renders this shape.
struct ScriptShape {
  enum class Kind { box, circle };
  Kind kind{Kind::box};
  bool solid_inside{true};  // "inside": the shape is solid; "outside": a cage
  double min_m[2]{};        // box: the lower left corner
  double max_m[2]{};        // box: the upper right corner
  double center_m[2]{};     // circle
  double radius_m{};        // circle
};

// At most this many entries in a script's `shapes`.
inline constexpr std::size_t kMaxScriptShapes = 256;

// Immutable, compiled at load time. Copyable; instances do not refer back to it. The
// fields from needs_velocity on are what compile_script found.
struct ScriptProgram {
  // "scripts/bumps.lua": names the chunk in every message (Lua shortens names over 59
  // characters to "..." and their end).
  std::string display_name;
  std::string source;        // Lua source text (binary chunks are refused)
  std::shared_ptr<const nlohmann::json> params_override;  // the JSON "params" object; null: none
  std::string error_context;   // e.g. the JSON file, "environments/lab.json"
  std::string pointer_prefix;  // e.g. "/effects/2/params"
  ScriptLimits limits;
  // The dimension of the scene the script was checked for: 1 (force(s) returns fx; s has
  // x, v, t, dt) or 2 (returns fx, fy; s has x, y, vx, vy, t, dt). Set by compile_script.
  int axes{1};
  bool needs_velocity{true};  // false: the engine may skip the velocity estimator
  bool needs_time{true};
  std::vector<ScriptParam> params;  // sorted by name
  // The script's `shapes`, in its order (2-D scenes only: a 1-D one refuses them).
  std::vector<ScriptShape> shapes;
};

// Load time: compiles and validates a script by creating one throwaway instance: syntax
// (text chunks only), top-level code within its budget, params and their overrides,
// needs, that force is a function; then calls reset() and force(s) once at
// x = 0, v = 0, t = 0, dt = 1 ms so typos inside force() are load errors too.
// `axes` is the dimension of the scene (1 or 2): the check call also counts what force
// returns, so a script written for the other dimension (one number in a 2-D scene, two
// in a 1-D one, or a field of the other kind such as s.y or s.v) is a load error that
// says so.
// Throws InputError:
//   syntax/runtime: "scripts/bumps.lua:12: message"
//   overrides:      "<error_context>: <pointer_prefix>/height: message"
//   limits:         "<error_context>: script limits: memory_bytes must be at least ..."
ScriptProgram compile_script(std::string display_name, std::string source,
                             const nlohmann::json& params_override, std::string error_context,
                             std::string pointer_prefix, ScriptLimits limits = {}, int axes = 1);

// Per run: owns one lua_State. create() and destruction allocate; force_N() and reset()
// never allocate on the C++ side, never throw and never block.
class ScriptInstance {
 public:
  // Runs the same load steps as compile_script (not its check call), so it throws
  // InputError only for a program that compile_script did not make.
  static std::unique_ptr<ScriptInstance> create(const ScriptProgram& program);
  ~ScriptInstance();
  ScriptInstance(const ScriptInstance&) = delete;
  ScriptInstance& operator=(const ScriptInstance&) = delete;

  // The script's force in N: force(s) must return N finite numbers in a scene of N axes
  // (one in 1-D; fx, fy in 2-D). Returns 0 N once disabled. The first runtime error,
  // limit overrun, or return value that is not that (a count of values not N, a nil, a
  // nan) disables the script and records fault_message(); later calls do not run the
  // script. Each instance is called with the input of its program's dimension only.
  template <int N>
  Axes<N> force_N(const ScriptInputOf<N>& input) noexcept;
  // Calls the script's reset() if it defines one (same limits as force). The host calls
  // it when a run starts or restarts; create() does not. Does not re-enable a disabled
  // script: its state may be half-updated; a new instance (a new run or a reload) starts
  // clean.
  void reset() noexcept;
  // Garbage collection, run by the host outside force() (in the tick's slack): the
  // collector is stopped inside force(). Returns at once when the heap has not grown
  // by more than a small slack since the last finished cycle (a non-allocating script
  // costs nothing); otherwise does up to max_steps incremental steps of about 1 KiB of
  // collector work each.
  void collect_garbage(int max_steps = 1) noexcept;
  // Brings the state's hot parts into the caches before a tick (the real-time loop calls
  // it while it spins to the deadline), without changing anything the script or the host
  // can see; never allocates, throws or blocks. When force() only reads and computes (its
  // code writes no upvalue, global or table and makes nothing: FunctionCode::reads_only)
  // and runs unhooked, and s holds the input of the last call, which succeeded: a dry
  // call, force(s) again with that s, whose results are dropped (it does exactly what that
  // call did). Otherwise, when force() runs unhooked: one protected call of a tiny
  // function of the sandbox's own that reads s.x (the call path). Else nothing.
  // A translated force (force_translated) is run instead, its results dropped: it has no
  // side effects.
  void warm() noexcept;
  // The real-time loop's dry tick (engine/run/warm_tick.hpp) runs the tick's own code on
  // a copy of the tick state, replaying the last tick. Between begin_dry_run() and
  // end_dry_run(), force_N() repeats the last call through its own
  // code when warm() would make a dry call and the input is bit for bit the one s holds
  // (the replay's), and otherwise warm() and answer 0 N; either way nothing changes that
  // the script or the host can see (no fault, no skipped call counted).
  void begin_dry_run() noexcept;
  void end_dry_run() noexcept;
  // How many times warm() or a dry run called force again (tests, telemetry).
  std::uint64_t dry_calls() const noexcept;

  bool disabled() const noexcept;
  // "scripts/bumps.lua:12: attempt to perform arithmetic on a nil value (global 'k')";
  // empty while not disabled. The host reports it once. (Loop thread, or after the run.)
  std::string_view fault_message() const noexcept;
  // Faults so far: 0, or 1 (the first fault disables the script).
  std::uint64_t fault_count() const noexcept;
  // What the fault was (ScriptFault::none while not disabled).
  ScriptFault fault() const noexcept;
  // force_N() calls answered with 0 N because the script is disabled.
  std::uint64_t skipped_calls() const noexcept;
  // Run time (s.t) of the call that faulted; 0 before any call.
  double fault_time_s() const noexcept;

  // Messages from log()/print(): a bounded queue (64 messages of up to 240 bytes), rate
  // limited per ScriptLimits; full or over-rate messages are dropped and counted. Appends
  // "scripts/x.lua:7: text (t = 0.500 s)" lines, then one line saying how many were
  // dropped, if any.
  void drain_log(std::vector<std::string>* out);

  // Telemetry and tests: live bytes of the Lua state, and how many growing allocations
  // it has made since creation.
  std::size_t memory_bytes() const noexcept;
  std::uint64_t allocation_count() const noexcept;
  // The length in VM instructions of force() when its own code cannot loop (it then runs
  // without the per-instruction count hook, charged that length per call), else 0.
  std::int64_t force_straight_line_instructions() const noexcept;
  // Whether force() now runs with no hook at all: it is straight-line, has no call
  // instruction, and no metatable the script set holds a function (so nothing it runs can
  // reach script code). Changes to false when the script sets such a metatable.
  bool force_runs_without_hooks() const noexcept;
  // Whether force(s) gets the table of values itself as `s` rather than the read-only
  // proxy: its code only reads constant fields of s (s.x), so s cannot be written or
  // escape; an unknown field is an error either way.
  bool force_reads_state_directly() const noexcept;
  // force(s) currently runs from its translation, without the VM: its bytecode is
  // straight-line arithmetic on fields of s and numeric upvalues and constants (see
  // engine/lua/force_program.hpp), the results are the VM's to the bit, and any result
  // that is not plainly good (not a finite number, or the wrong count) is asked of the VM
  // again, which then reports the fault as it always does.
  bool force_translated() const noexcept;

 private:
  friend ScriptProgram compile_script(std::string, std::string, const nlohmann::json&, std::string,
                                      std::string, ScriptLimits, int);
  // The load check: one call of force(s) at rest that counts what it returns (-1 when the
  // call failed: then the instance is disabled with its message).
  int check_force_results() noexcept;
  explicit ScriptInstance(std::unique_ptr<detail::ScriptVm> vm);
  std::unique_ptr<detail::ScriptVm> vm_;
};

}  // namespace hapscene
