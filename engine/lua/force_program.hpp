#pragma once
// Internal: a force(s) that is straight-line arithmetic on numbers, run without the Lua VM.
//
// Most lab scripts' force is a formula: `return -K * (s.x - x0)`, or a comparison and two
// returns. Its bytecode can be read (bytecode.hpp) and, when every value it touches is a
// number (fields of s, numeric upvalues, numeric constants) and every instruction is one
// of a small set (moves, loads, float arithmetic, comparisons, forward jumps, returns),
// translated into a program over an array of doubles that computes the same results to
// the bit: Lua's float arithmetic is the C library's (the same `fmod`, `pow`, `floor`,
// with Lua's rules for `%`, `//` and `^ 2` reproduced), and a translation is refused
// wherever Lua would use integer arithmetic (an operation on two integers) or could
// raise (a missing field, a non-number). What cannot be translated runs in the VM.
//
// Such a force has no side effects: calling it, or not, changes nothing else, so the VM
// can always be asked instead (ScriptInstance falls back to it for any result that is not
// plainly good, and the VM then reports the fault exactly as it always has).
#include <lua.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "engine/lua/bytecode.hpp"
#include "engine/lua/state_fields.hpp"

namespace hapscene::detail {


class ForceProgram {
 public:
  // Translates the function at `function_index` (its chunk already read into `chunk`),
  // whose first parameter is s and is only read by constant field (bytecode.hpp);
  // `fields[f]` is the name of field f (state_fields.hpp) in this scene, nullptr where s
  // has no such field (reading one is an error in Lua).
  // Reads the upvalues' current values. nullopt: not translatable.
  static std::optional<ForceProgram> translate(const FunctionChunk& chunk,
                                               const std::array<const char*, kFieldCount>& fields, lua_State* L,
                                               int function_index);

  // Reads the upvalues again (after Lua code ran: reset()). False when one is no longer a
  // number of the kind the translation assumed: the program must not run any more.
  bool read_upvalues(lua_State* L, int function_index) noexcept;

  // The value of s.<field> for the next run (field: state_fields.hpp).
  void set_field(int field, double value) noexcept { values_[static_cast<std::size_t>(field)] = value; }

  // The most values a translated force hands back: a force that returns more (a scene of
  // more axes) still runs, but in the VM.
  static constexpr int kMaxResults = 2;

  // Runs the program; writes up to kMaxResults results to `results` and returns how many
  // values the function returned (0, 1, 2 or more).
  int run(double* results) noexcept;

 private:
  enum class Kind : std::uint8_t {
    copy, negate, add, sub, mul, div, mod, pow, floor_div,   // values[a] = values[b] op values[c]
    branch_lt, branch_le, branch_eq,                         // if ((b op c) != expect) goto op a
    jump, give_back                                          // jump: to op a; give_back: count a, values b, c
  };
  struct Op {  // 8 bytes: one load
    Kind kind{};
    bool expect{};
    std::uint16_t a{}, b{}, c{};
  };
  struct Upvalue {
    int index{};    // 1-based, for lua_getupvalue
    int slot{};
    bool integer{};  // the value was an integer at translation
  };

  // Runs ops from the first to a give_back on the values `v`; returns its count.
  [[gnu::always_inline]] static inline int execute(const Op* ops, double* v, double* results) noexcept;

  std::vector<Op> ops_;
  // Ops whose operands are all constants and upvalues, taken out of the run: read_upvalues
  // runs them once (they cannot fail: float arithmetic does not trap). Ends with a give_back.
  std::vector<Op> invariant_ops_;
  // The fields of s (slot = field index), the registers, then constants and upvalues.
  std::vector<double> values_;
  std::vector<Upvalue> upvalues_;
};

}  // namespace hapscene::detail
