// The sandbox: which standard functions a script sees, and replacements for the ones
// that would let it escape, stall the host, or run code outside the budget.
//
// Allowed: the safe parts of base, math, string, table, utf8 and coroutine. Not there:
// io, os, debug, package/require, load/loadstring/dofile/loadfile, warn, string.dump,
// string.pack/unpack, and the string pattern functions (find, match, gmatch, gsub): one
// pattern call can backtrack for seconds inside C, where no hook can stop it.
// Replaced: setmetatable (freezes a copy of the metatable; refuses __gc, __mode and long
// or looping __index chains), collectgarbage ("count" only: the host runs the collector),
// print (= log).
// Charged: library functions whose C loops depend on their arguments (table.sort, insert,
// remove, move, concat, unpack, string.rep, string.byte, utf8 scans) subtract their work
// from the instruction budget before they run.
#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>
#include <string_view>

#include "engine/lua/script_vm.hpp"

namespace hapscene::detail {
namespace {

constexpr std::array kBaseNames{
    "assert", "error", "getmetatable", "ipairs",   "next",   "pairs",    "pcall",  "rawequal",
    "rawget", "rawlen", "rawset",      "select",   "tonumber", "tostring", "type",  "xpcall",
    "_VERSION"};
constexpr std::array kStringNames{"byte", "char", "format", "len", "lower",
                                  "rep",  "reverse", "sub", "upper"};
constexpr std::array kTableNames{"concat", "insert", "move", "pack", "remove", "sort", "unpack"};
constexpr std::array kUtf8Names{"char", "charpattern", "codepoint", "codes", "len", "offset"};
constexpr std::array kCoroutineNames{"close",  "create",  "isyieldable", "resume",
                                     "running", "status", "wrap",        "yield"};

// ---- Charged library functions ------------------------------------------------------

// Calls the wrapped original (upvalue 1) with all arguments and returns its results.
int call_original(lua_State* L) {
  const int n = lua_gettop(L);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, n, LUA_MULTRET);
  return lua_gettop(L);
}

// Elements in [first, last], saturating instead of overflowing.
std::int64_t span(lua_Integer first, lua_Integer last) {
  if (last < first) return 0;
  const auto count = static_cast<unsigned long long>(last) - static_cast<unsigned long long>(first);
  return count >= (1ull << 62) ? (1ll << 62) : static_cast<std::int64_t>(count) + 1;
}

// #t (honours __len), or 0 when the argument is not a table.
lua_Integer length_of(lua_State* L, int index) {
  return lua_type(L, index) == LUA_TTABLE ? luaL_len(L, index) : 0;
}

// __len of a fixed-length proxy: upvalue 1.
int fixed_length(lua_State* L) {
  lua_pushvalue(L, lua_upvalueindex(1));
  return 1;
}

// A __len metamethod is script code: asked again by the original function, it may answer
// a different length than the one charged (a negative one first, a huge one next), and
// the original's C loop would run uncharged. So a table with __len is handed to the
// original as a proxy whose length is fixed at `length`; reads and writes go through to
// the table (its own __index and __newindex included).
void fix_length(lua_State* L, int index, lua_Integer length) {
  if (lua_type(L, index) != LUA_TTABLE || luaL_getmetafield(L, index, "__len") == LUA_TNIL) return;
  lua_pop(L, 1);
  lua_createtable(L, 0, 0);
  lua_createtable(L, 0, 3);
  lua_pushvalue(L, index);
  lua_setfield(L, -2, "__index");
  lua_pushvalue(L, index);
  lua_setfield(L, -2, "__newindex");
  lua_pushinteger(L, length);
  lua_pushcclosure(L, fixed_length, 1);
  lua_setfield(L, -2, "__len");
  lua_setmetatable(L, -2);
  lua_replace(L, index);
}

// table.sort: about n log2 n comparisons.
int charged_sort(lua_State* L) {
  const lua_Integer n = length_of(L, 1);
  std::int64_t log2n = 1;
  while (log2n < 62 && (lua_Integer{1} << log2n) < n) ++log2n;
  charge(L, n > (1ll << 40) ? (1ll << 62) : n * log2n);
  fix_length(L, 1, n);
  return call_original(L);
}

// table.insert(t, pos, v) and table.remove(t, pos) shift up to #t elements; appending
// (insert with two arguments, remove with one) is one step.
int charged_insert(lua_State* L) {
  if (lua_gettop(L) >= 3) {
    const lua_Integer n = length_of(L, 1);
    charge(L, span(1, n));
    fix_length(L, 1, n);
  }
  return call_original(L);
}
int charged_remove(lua_State* L) {
  if (lua_gettop(L) >= 2) {
    const lua_Integer n = length_of(L, 1);
    charge(L, span(1, n));
    fix_length(L, 1, n);
  }
  return call_original(L);
}

// table.move(a1, f, e, t [, a2]) copies e - f + 1 elements.
int charged_move(lua_State* L) {
  charge(L, span(luaL_checkinteger(L, 2), luaL_checkinteger(L, 3)));
  return call_original(L);
}

// table.concat(t, sep, i, j) and table.unpack(t, i, j) visit j - i + 1 elements. The
// range is passed on explicitly, so the original never asks __len again.
// (table.unpack takes the length of anything, as the original does: "abc" has 3.)
int charged_range(lua_State* L, int first_arg) {
  const lua_Integer first = luaL_optinteger(L, first_arg, 1);
  const bool any_length = first_arg == 2;
  const lua_Integer last = !lua_isnoneornil(L, first_arg + 1) ? luaL_checkinteger(L, first_arg + 1)
                           : any_length                        ? luaL_len(L, 1)
                                                               : length_of(L, 1);
  charge(L, span(first, last));
  fix_length(L, 1, last);  // concat asks the length even when given the range
  if (lua_gettop(L) < first_arg + 1) lua_settop(L, first_arg + 1);
  lua_pushinteger(L, first);
  lua_replace(L, first_arg);
  lua_pushinteger(L, last);
  lua_replace(L, first_arg + 1);
  return call_original(L);
}
int charged_concat(lua_State* L) { return charged_range(L, 3); }
int charged_unpack(lua_State* L) { return charged_range(L, 2); }

// string.rep: refuses a result over the string limit before doing any work (the C loop
// would otherwise copy it piece by piece), then charges one instruction per piece.
int checked_rep(lua_State* L) {
  std::size_t length = 0;
  std::size_t separator = 0;
  luaL_checklstring(L, 1, &length);
  const lua_Integer n = luaL_checkinteger(L, 2);
  luaL_optlstring(L, 3, "", &separator);
  if (n > 0) {
    ScriptVm* vm = vm_of(L);
    const double total = static_cast<double>(n) * static_cast<double>(length) +
                         static_cast<double>(n - 1) * static_cast<double>(separator);
    if (total > static_cast<double>(vm->limits.string_bytes)) {
      char where[160];
      describe_position(L, 1, vm, where, sizeof where);
      record_fault(vm, ScriptFault::memory_limit,
                   "%s: string limit exceeded (string.rep would make %.0f bytes; limit %zu)",
                   where, total, vm->limits.string_bytes);
      trip(vm, L);
      return raise_tripped(L);
    }
    charge(L, n);
  }
  return call_original(L);
}

// string.byte(s, i, j) and utf8.codepoint(s, i, j) visit bytes i..j (j defaults to i;
// negative positions count from the end).
int charged_bytes(lua_State* L) {
  std::size_t size = 0;
  luaL_checklstring(L, 1, &size);
  const auto length = static_cast<lua_Integer>(size);
  const auto absolute = [length](lua_Integer position) {
    return position < 0 ? length + position + 1 : position;
  };
  const lua_Integer first = absolute(luaL_optinteger(L, 2, 1));
  const lua_Integer last = absolute(luaL_optinteger(L, 3, first));
  charge(L, std::min<std::int64_t>(span(first, last), length));
  return call_original(L);
}

// utf8.len and utf8.offset scan the string: one instruction per 8 bytes.
int charged_scan(lua_State* L) {
  std::size_t length = 0;
  luaL_checklstring(L, 1, &length);
  charge(L, static_cast<std::int64_t>(length / 8 + 1));
  return call_original(L);
}

// Replaces table[name] (at `index`) by `wrapper` with the original as its upvalue.
void wrap(lua_State* L, int index, const char* name, lua_CFunction wrapper) {
  index = lua_absindex(L, index);
  lua_getfield(L, index, name);
  lua_pushcclosure(L, wrapper, 1);
  lua_setfield(L, index, name);
}

// ---- Replacements -------------------------------------------------------------------

// ---- setmetatable: frozen metatables --------------------------------------------------
//
// A metatable is copied when it is set: the table gets a private copy of its metamethods,
// and later changes to the script's table have no effect (getmetatable still answers the
// script's table). Frozen, the metamethods can be checked once, here:
// - no __gc: Lua runs finalizers with hooks off, so an endless one would hang the host's
//   collector (Lua registers a finalizer only when __gc is there at setmetatable time);
// - no __mode: the collector clears weak tables in one step that no one can interrupt,
//   and with weak keys (ephemerons) it iterates to convergence, which can grow faster
//   than their size;
// - __index and __newindex chains of tables at most kMaxChainDepth long, and no loops:
//   Lua follows up to 2000 of them inside one instruction, each a table lookup.
// Chains stay bounded because a table that some frozen metatable names as __index or
// __newindex (a "target") may later get a new metatable only if its chain does not grow.

// Keys of the copies (light userdata: no script can name them) and of the registry set.
const char kProtectedKey = 0;  // copy[&kProtectedKey]: the original had __metatable
const char kDepthKey = 0;      // copy[&kDepthKey]: tables from here to the chain's end
const char kTargetsKey = 0;    // registry: weak-keyed set of tables named by a copy

constexpr int kMaxChainDepth = 16;

// The events Lua and its libraries look up in a metatable (raw), but __gc and __mode.
constexpr std::array kEvents{"__index", "__newindex", "__len",  "__eq",     "__lt",   "__le",
                             "__unm",   "__add",      "__sub",  "__mul",    "__div",  "__mod",
                             "__pow",   "__idiv",     "__band", "__bor",    "__bxor", "__shl",
                             "__shr",   "__bnot",     "__concat", "__call", "__close",
                             "__tostring", "__name",  "__pairs"};

// Chain depth of the table at `index`: 0 without a metatable; a metatable the sandbox
// made itself (s, libraries, globals, params) is one table deep at most.
lua_Integer chain_depth(lua_State* L, int index) {
  if (lua_getmetatable(L, index) == 0) return 0;
  const lua_Integer depth = lua_rawgetp(L, -1, &kDepthKey) == LUA_TNUMBER ? lua_tointeger(L, -1) : 1;
  lua_pop(L, 2);
  return depth;
}

bool is_target(lua_State* L, int index) {
  index = lua_absindex(L, index);
  lua_rawgetp(L, LUA_REGISTRYINDEX, &kTargetsKey);
  lua_pushvalue(L, index);
  const bool target = lua_rawget(L, -2) != LUA_TNIL;
  lua_pop(L, 2);
  return target;
}

// Whether the current metatable of the table at `index` forbids changing it.
bool protected_metatable(lua_State* L, int index) {
  if (lua_getmetatable(L, index) == 0) return false;
  bool is_protected = false;
  if (lua_rawgetp(L, -1, &kProtectedKey) == LUA_TBOOLEAN) {
    is_protected = lua_toboolean(L, -1) != 0;
  } else {
    lua_pushliteral(L, "__metatable");
    is_protected = lua_rawget(L, -3) != LUA_TNIL;
    lua_pop(L, 1);
  }
  lua_pop(L, 2);
  return is_protected;
}

int sandbox_setmetatable(lua_State* L) {
  luaL_checktype(L, 1, LUA_TTABLE);
  const int type = lua_type(L, 2);
  luaL_argexpected(L, type == LUA_TNIL || type == LUA_TTABLE, 2, "nil or table");
  lua_settop(L, 2);
  if (protected_metatable(L, 1)) return luaL_error(L, "cannot change a protected metatable");
  if (type == LUA_TNIL) {
    lua_setmetatable(L, 1);
    return 1;  // the table, now on top
  }
  for (const char* refused : {"__gc", "__mode"}) {
    lua_pushstring(L, refused);
    const bool present = lua_rawget(L, 2) != LUA_TNIL;
    lua_pop(L, 1);
    if (!present) continue;
    if (std::strcmp(refused, "__gc") == 0) {
      return luaL_error(L, "setmetatable: __gc finalizers are not allowed in scripts "
                           "(they would run outside the instruction budget)");
    }
    return luaL_error(L, "setmetatable: weak tables (__mode) are not allowed in scripts (the "
                         "collector clears them in one step that cannot be interrupted)");
  }
  charge(L, static_cast<std::int64_t>(kEvents.size()));

  // The copy (3), its chain depth, and the tables it names.
  const lua_Integer old_depth = chain_depth(L, 1);
  lua_createtable(L, 0, 4);
  lua_Integer depth = 0;
  for (const char* event : kEvents) {
    lua_pushstring(L, event);
    const int event_type = lua_rawget(L, 2);
    if (event_type == LUA_TNIL) {
      lua_pop(L, 1);
      continue;
    }
    // An operator or field read may now call a function (script code, or a C function
    // that calls script code, such as pcall): force() can no longer run unhooked.
    if (event_type == LUA_TFUNCTION) vm_of(L)->script_metamethods = true;
    const bool chain = std::strcmp(event, "__index") == 0 || std::strcmp(event, "__newindex") == 0;
    if (chain && lua_type(L, -1) == LUA_TTABLE) {
      depth = std::max(depth, 1 + chain_depth(L, -1));
      lua_rawgetp(L, LUA_REGISTRYINDEX, &kTargetsKey);
      lua_pushvalue(L, -2);
      lua_pushboolean(L, 1);
      lua_rawset(L, -3);
      lua_pop(L, 1);
    }
    lua_setfield(L, 3, event);
  }
  if (depth > kMaxChainDepth) {
    return luaL_error(L, "setmetatable: __index/__newindex chains longer than %d tables are not "
                         "allowed in scripts", kMaxChainDepth);
  }
  if (depth > old_depth && is_target(L, 1)) {
    return luaL_error(L, "setmetatable: this table is the __index or __newindex of another "
                         "table, so its own chain cannot grow (it would make a loop or a long chain)");
  }
  // getmetatable(t) answers the script's table, or its __metatable field.
  lua_pushliteral(L, "__metatable");
  const bool has_protection = lua_rawget(L, 2) != LUA_TNIL;
  if (!has_protection) {
    lua_pop(L, 1);
    lua_pushvalue(L, 2);
  }
  lua_setfield(L, 3, "__metatable");
  lua_pushboolean(L, has_protection ? 1 : 0);
  lua_rawsetp(L, 3, &kProtectedKey);
  lua_pushinteger(L, depth);
  lua_rawsetp(L, 3, &kDepthKey);
  lua_setmetatable(L, 1);
  lua_settop(L, 1);
  return 1;
}

// collectgarbage("count") only: stopping or running the collector is the host's job.
int sandbox_collectgarbage(lua_State* L) {
  const char* option = luaL_optstring(L, 1, "collect");
  if (std::strcmp(option, "count") == 0) {
    lua_pushnumber(L, static_cast<lua_Number>(vm_of(L)->bytes) / 1024.0);
    return 1;
  }
  return luaL_error(L, "collectgarbage(\"%s\") is not available in scripts (the host runs the "
                       "collector between ticks); only collectgarbage(\"count\") is", option);
}

// log(...) and print(...): like print, into the script's log queue. Never blocks: over the
// rate or with the queue full the message is dropped and counted.
int script_log(lua_State* L) {
  ScriptVm* vm = vm_of(L);
  if (vm->log_writing) return 0;  // log() from a __tostring inside log(): ignored
  if (!vm->log.admit(vm->now_s)) return 0;
  char* text = vm->log.begin_write();
  if (text == nullptr) return 0;
  vm->log_writing = true;  // cleared here, or by the next call if __tostring raises
  constexpr std::size_t capacity = LogQueue::kTextBytes;
  char where[160];
  describe_position(L, 1, vm, where, sizeof where);
  int written = std::snprintf(text, capacity, "%s: ", where);
  std::size_t used = written < 0 ? 0 : static_cast<std::size_t>(written);
  if (used > capacity) used = capacity;
  bool truncated = false;
  const int n = lua_gettop(L);
  for (int i = 1; i <= n; ++i) {
    std::size_t length = 0;
    // May call __tostring (a Lua function, within the budget). If it raises, the slot is
    // simply not published.
    const char* piece = luaL_tolstring(L, i, &length);
    if (i > 1) length += 1;
    const std::size_t room = capacity - used;
    const std::size_t copied = length < room ? length : room;
    if (i > 1 && copied > 0) {
      text[used] = '\t';
      std::memcpy(text + used + 1, piece, copied - 1);
    } else {
      std::memcpy(text + used, piece, copied);
    }
    used += copied;
    truncated = truncated || copied < length;
    lua_pop(L, 1);
  }
  if (truncated && used >= 3) std::memcpy(text + used - 3, "...", 3);
  vm->log.commit(vm->now_s, used);
  vm->log_writing = false;
  return 0;
}

// ---- Building the sandbox -----------------------------------------------------------

// Opens a standard library and copies the allowed names into a new table env[name].
template <std::size_t N>
void copy_library(lua_State* L, int env, const char* name, lua_CFunction open,
                  const std::array<const char*, N>& allowed) {
  luaL_requiref(L, name, open, 0);
  lua_createtable(L, 0, static_cast<int>(N));
  for (const char* field : allowed) {
    lua_getfield(L, -2, field);
    lua_setfield(L, -2, field);
  }
  lua_setfield(L, env, name);
  lua_pop(L, 1);
}

// math: every function, seeded with 0 so that runs are reproducible.
void copy_math(lua_State* L, int env) {
  luaL_requiref(L, LUA_MATHLIBNAME, luaopen_math, 0);
  lua_newtable(L);
  lua_pushnil(L);
  while (lua_next(L, -3) != 0) {
    lua_pushvalue(L, -2);
    lua_insert(L, -2);
    lua_rawset(L, -4);
  }
  lua_getfield(L, -1, "randomseed");
  lua_pushinteger(L, 0);
  lua_call(L, 1, 0);
  lua_setfield(L, env, LUA_MATHLIBNAME);
  lua_pop(L, 1);
}

// Makes unknown fields of the library table at `index` errors (see library_index).
void seal_library(lua_State* L, int index, const char* name) {
  index = lua_absindex(L, index);
  lua_createtable(L, 0, 2);
  lua_pushstring(L, name);
  lua_pushcclosure(L, library_index, 1);
  lua_setfield(L, -2, "__index");
  lua_pushboolean(L, 0);
  lua_setfield(L, -2, "__metatable");
  lua_setmetatable(L, index);
}

// A fresh table with every field of the table at `index`.
void push_copy(lua_State* L, int index) {
  index = lua_absindex(L, index);
  lua_newtable(L);
  lua_pushnil(L);
  while (lua_next(L, index) != 0) {
    lua_pushvalue(L, -2);
    lua_insert(L, -2);
    lua_rawset(L, -4);
  }
}

// String methods ("x"):upper() use a private copy of the sandboxed string table, and the
// metatable hides itself: getmetatable("") is false, so a script cannot reach or change
// what methods every string has. Arithmetic on strings ("10" + 1) is gone with it.
void protect_string_metatable(lua_State* L, int env) {
  lua_pushliteral(L, "");
  lua_createtable(L, 0, 2);
  lua_getfield(L, env, LUA_STRLIBNAME);
  push_copy(L, -1);
  seal_library(L, -1, LUA_STRLIBNAME);
  lua_setfield(L, -3, "__index");
  lua_pop(L, 1);
  lua_pushboolean(L, 0);
  lua_setfield(L, -2, "__metatable");
  lua_setmetatable(L, -2);
  lua_pop(L, 1);
}

}  // namespace

int global_index(lua_State* L);     // globals.cpp
int global_newindex(lua_State* L);  // globals.cpp

int open_sandbox(lua_State* L) {
  lua_settop(L, 0);
  prepare_suggestions(L);
  // The set of chain targets (see sandbox_setmetatable): weak keys, values true, so the
  // collector clears it in one linear pass.
  lua_createtable(L, 0, 0);
  lua_createtable(L, 0, 1);
  lua_pushliteral(L, "k");
  lua_setfield(L, -2, "__mode");
  lua_setmetatable(L, -2);
  lua_rawsetp(L, LUA_REGISTRYINDEX, &kTargetsKey);
  lua_newtable(L);
  const int env = 1;

  // Base functions, from the real global table, which scripts never see.
  luaL_requiref(L, "_G", luaopen_base, 0);
  for (const char* name : kBaseNames) {
    lua_getfield(L, -1, name);
    lua_setfield(L, env, name);
  }
  lua_pop(L, 1);
  lua_pushcfunction(L, sandbox_setmetatable);
  lua_setfield(L, env, "setmetatable");
  lua_pushcfunction(L, sandbox_collectgarbage);
  lua_setfield(L, env, "collectgarbage");
  lua_pushcfunction(L, script_log);
  lua_setfield(L, env, "log");
  lua_pushcfunction(L, script_log);
  lua_setfield(L, env, "print");
  lua_pushvalue(L, env);
  lua_setfield(L, env, "_G");

  // Libraries, copied into fresh tables; then the charged wrappers.
  copy_math(L, env);
  copy_library(L, env, LUA_STRLIBNAME, luaopen_string, kStringNames);
  copy_library(L, env, LUA_TABLIBNAME, luaopen_table, kTableNames);
  copy_library(L, env, LUA_UTF8LIBNAME, luaopen_utf8, kUtf8Names);
  copy_library(L, env, LUA_COLIBNAME, luaopen_coroutine, kCoroutineNames);
  lua_getfield(L, env, LUA_TABLIBNAME);
  wrap(L, -1, "sort", charged_sort);
  wrap(L, -1, "insert", charged_insert);
  wrap(L, -1, "remove", charged_remove);
  wrap(L, -1, "move", charged_move);
  wrap(L, -1, "concat", charged_concat);
  wrap(L, -1, "unpack", charged_unpack);
  lua_pop(L, 1);
  lua_getfield(L, env, LUA_STRLIBNAME);
  wrap(L, -1, "rep", checked_rep);
  wrap(L, -1, "byte", charged_bytes);
  lua_pop(L, 1);
  lua_getfield(L, env, LUA_UTF8LIBNAME);
  wrap(L, -1, "codepoint", charged_bytes);
  wrap(L, -1, "len", charged_scan);
  wrap(L, -1, "offset", charged_scan);
  lua_pop(L, 1);
  protect_string_metatable(L, env);
  for (const char* library : {LUA_MATHLIBNAME, LUA_STRLIBNAME, LUA_TABLIBNAME, LUA_UTF8LIBNAME,
                              LUA_COLIBNAME}) {
    lua_getfield(L, env, library);
    seal_library(L, -1, library);
    lua_pop(L, 1);
  }

  // Strict globals: reading an undefined one is an error; so is creating one while
  // running (see globals.cpp). The metatable is hidden.
  set_guard_metatable(L, env, global_index, global_newindex);

  // The sandbox table becomes the global table, so the chunk's _ENV is the sandbox.
  lua_pushvalue(L, env);
  lua_rawseti(L, LUA_REGISTRYINDEX, LUA_RIDX_GLOBALS);
  return 0;
}

}  // namespace hapscene::detail
