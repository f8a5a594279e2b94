#pragma once
// Internal: what the instruction budget needs to know about a compiled Lua function.
#include <lua.hpp>

#include <cstdint>

namespace hapscene::detail {

// The number of VM instructions of the Lua function at `index` when its own code cannot
// loop (no backward jump of any kind: every instruction runs at most once per call), or 0
// when it can loop, is not a Lua function, or its bytecode is not Lua 5.4's. Calls it
// makes are not covered: they are counted when they happen (see budget.cpp).
std::int64_t straight_line_length(lua_State* L, int index);

}  // namespace hapscene::detail
