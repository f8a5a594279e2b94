// What a script's global names mean: strict globals and library tables, load errors, and
// the checks run after the chunk has loaded. The `params` table is params_table.cpp's,
// `needs` and the state table `s` state_table.cpp's, the `shapes` list script_shapes.cpp's,
// and the suggestions of a failed lookup suggestions.cpp's.
#include <cstdarg>
#include <cstdio>
#include <cstring>

#include "engine/lua/script_vm.hpp"

namespace hapscene::detail {

void set_load_error(ScriptVm* vm, const char* format, ...) {
  char text[512];
  std::va_list args;
  va_start(args, format);
  std::vsnprintf(text, sizeof text, format, args);
  va_end(args);
  try {
    if (vm->load_error.empty()) vm->load_error = text;
  } catch (...) {
    record_fault(vm, ScriptFault::error, "%s", text);
  }
}

// ---- Strict globals ------------------------------------------------------------------

// Reading a global that does not exist: an error naming it and the nearest name, or
// saying that the sandbox leaves it out on purpose.
int global_index(lua_State* L) {
  if (lua_type(L, 2) != LUA_TSTRING) return luaL_error(L, "undefined global [%s]", luaL_typename(L, 2));
  const char* name = lua_tostring(L, 2);
  for (const char* removed : {"io", "os", "debug", "package", "require", "load", "loadstring",
                              "dofile", "loadfile", "warn", "module", "setfenv", "getfenv"}) {
    if (std::strcmp(name, removed) == 0) {
      return luaL_error(L, "undefined global '%s' (scripts run in a sandbox without it; see "
                           "docs/reference/lua.md)", name);
    }
  }
  if (std::strcmp(name, "unpack") == 0) {
    return luaL_error(L, "undefined global 'unpack' (use table.unpack)");
  }
  return raise_lookup_error(L, PendingSuggestion::Kind::global, "", "undefined global '%s'", name);
}

// Creating a global: fine while loading (that is how a script declares its state and
// functions), an error while running (a typo, or per-tick allocation in the global table).
int global_newindex(lua_State* L) {
  ScriptVm* vm = vm_of(L);
  const bool named = lua_type(L, 2) == LUA_TSTRING;
  if (vm->phase == Phase::loading) {
    if (named && std::strcmp(lua_tostring(L, 2), "params") == 0) return assign_params(L);
    lua_rawset(L, 1);
    return 0;
  }
  return luaL_error(L, "cannot create global '%s' while running (declare it at the top level "
                       "of the script, or use a local)", named ? lua_tostring(L, 2) : "?");
}

// ---- Strict library tables --------------------------------------------------------------

// string.fnd (a typo) or string.find (left out): an error saying which. Upvalue 1 is the
// library's name.
int library_index(lua_State* L) {
  const char* library = lua_tostring(L, lua_upvalueindex(1));
  if (lua_type(L, 2) != LUA_TSTRING) {
    return luaL_error(L, "%s has no field [%s]", library, luaL_typename(L, 2));
  }
  const char* name = lua_tostring(L, 2);
  if (std::strcmp(library, "string") == 0) {
    for (const char* pattern : {"find", "match", "gmatch", "gsub"}) {
      if (std::strcmp(name, pattern) == 0) {
        return luaL_error(L, "string.%s is not available in scripts (a string pattern can run "
                             "for seconds inside one call, where the budget cannot stop it)", name);
      }
    }
    for (const char* removed : {"dump", "pack", "unpack", "packsize"}) {
      if (std::strcmp(name, removed) == 0) {
        return luaL_error(L, "string.%s is not available in scripts", name);
      }
    }
  }
  // The format names the library; the name is the one argument.
  char format[48];
  std::snprintf(format, sizeof format, "%s has no field '%%s'", library);
  return raise_lookup_error(L, PendingSuggestion::Kind::library, library, format, name);
}

// ---- After the chunk has run -----------------------------------------------------------

int finish_load(lua_State* L) {
  ScriptVm* vm = vm_of(L);
  const char* name = vm->display_name.c_str();
  lua_settop(L, 0);
  lua_rawgeti(L, LUA_REGISTRYINDEX, LUA_RIDX_GLOBALS);  // 1: the script's globals
  const int env = 1;

  // force (2), required.
  lua_pushliteral(L, "force");
  lua_rawget(L, env);
  if (lua_isnil(L, 2)) {
    set_load_error(vm, "%s: the script must define a global function force(s) that returns the "
                       "force in N", name);
    return raise_tripped(L);
  }
  if (!lua_isfunction(L, 2)) {
    set_load_error(vm, "%s: force must be a function, got a %s", name, luaL_typename(L, 2));
    return raise_tripped(L);
  }

  // reset (3), optional.
  lua_pushliteral(L, "reset");
  lua_rawget(L, env);
  if (!lua_isnil(L, 3) && !lua_isfunction(L, 3)) {
    set_load_error(vm, "%s: reset must be a function, got a %s", name, luaL_typename(L, 3));
    return raise_tripped(L);
  }

  // needs, optional.
  lua_pushliteral(L, "needs");
  lua_rawget(L, env);
  if (!check_needs(L, 4, vm)) return raise_tripped(L);
  lua_settop(L, 3);

  // shapes, optional (2-D scripts: compile_script refuses them in a 1-D scene).
  lua_pushliteral(L, "shapes");
  lua_rawget(L, env);
  if (!check_shapes(L, 4, vm)) return raise_tripped(L);
  lua_settop(L, 3);

  // params: a script without one gets an empty sealed table (and overrides are errors);
  // one that replaced its table after declaring it is told to use one table.
  if (!finish_params(L, env, vm)) return raise_tripped(L);
  lua_settop(L, 3);

  // Where force is defined, for messages about what it returns.
  lua_Debug ar{};
  lua_pushvalue(L, 2);
  lua_getinfo(L, ">S", &ar);
  vm->force_line = ar.linedefined;

  // Results, in slot order: force, reset, s, data, then each field's name (state_fields.hpp;
  // "" for a field this scene does not have: its slot is never used).
  push_state_tables(L, vm);
  for (int f = 0; f < kFieldCount; ++f) {
    const char* field_name = state_field_name(f, vm->axes);
    lua_pushstring(L, field_name != nullptr ? field_name : "");
  }
  return kSlotCount;
}

void set_guard_metatable(lua_State* L, int index, lua_CFunction on_index, lua_CFunction on_newindex) {
  index = lua_absindex(L, index);
  lua_createtable(L, 0, 3);
  lua_pushcfunction(L, on_index);
  lua_setfield(L, -2, "__index");
  lua_pushcfunction(L, on_newindex);
  lua_setfield(L, -2, "__newindex");
  lua_pushboolean(L, 0);
  lua_setfield(L, -2, "__metatable");
  lua_setmetatable(L, index);
}

}  // namespace hapscene::detail
