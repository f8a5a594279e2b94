#pragma once
// Internal: what the instruction budget needs to know about a compiled Lua function.
#include <lua.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace hapscene::detail {

// The number of VM instructions of the Lua function at `index` when its own code cannot
// loop (no backward jump of any kind: every instruction runs at most once per call), or 0
// when it can loop, is not a Lua function, or its bytecode is not Lua 5.4's. Calls it
// makes are not covered: they are counted when they happen (see budget.cpp).
// `calls` (when given) is set to whether the function's own code has a call instruction
// (a call or a tail call); true whenever the answer is 0.
std::int64_t straight_line_length(lua_State* L, int index, bool* calls = nullptr);

// One constant of a function's constant table.
struct LuaConstant {
  enum class Kind { other, integer, number, string };  // other: nil, false, true
  Kind kind{Kind::other};
  std::int64_t integer{};
  double number{};
  std::string text;
};

// A Lua 5.4 function's own code, as lua_dump writes it (nested functions are not read).
struct FunctionChunk {
  int parameters{};  // fixed parameters: registers 0 .. parameters - 1 on entry
  bool vararg{};
  int stack_size{};  // registers the function uses
  std::vector<std::uint32_t> code;
  std::vector<LuaConstant> constants;
  int upvalue_count{};
};
// Reads the Lua function at `index`; false (and an empty chunk) when it is not a Lua 5.4
// function or its dump cannot be read.
bool read_function_chunk(lua_State* L, int index, FunctionChunk* out);

// What read_function_code found in a Lua function's own code (not in what it calls).
struct FunctionCode {
  std::int64_t straight_line_length{};  // as straight_line_length answers
  bool calls{true};                     // has a call or tail call instruction
  // Its first parameter is only ever read as the table of a constant field (`s.x`): never
  // written, copied, passed, returned, stored, captured or used as an operand, so the
  // value passed there cannot escape the call or be changed by it.
  bool first_parameter_read_by_field_only{};
  // Every instruction only reads or computes: loads, reads of upvalues, globals and table
  // fields, arithmetic, comparisons, tests, forward jumps and returns. None writes an
  // upvalue, a global or a table field, makes a table, a string (concatenation) or a
  // closure, calls, loops, closes a variable or touches varargs. Such a function, given
  // the same arguments in the same state, does the same and leaves the state as it was
  // (what a metamethod an operator reaches does is the caller's to rule out).
  bool reads_only{};
};
// Reads the code of the Lua function at `index`; the defaults (can loop, calls, the
// parameter may escape) when it is not a Lua 5.4 function.
FunctionCode read_function_code(lua_State* L, int index);

}  // namespace hapscene::detail
