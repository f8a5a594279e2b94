// What a script reads of the tick: the `needs` it declares (velocity, time) and the
// read-only state table `s` with the fields of its scene's axes (state_fields.hpp).
#include <cstdio>
#include <cstring>

#include "engine/base/units.hpp"
#include "engine/lua/script_vm.hpp"

namespace hapscene::detail {
namespace {

// s.xx (a typo), or s.v when the script said it does not need velocity.
int state_index(lua_State* L) {
  const ScriptVm* vm = vm_of(L);
  if (lua_type(L, 2) != LUA_TSTRING) return luaL_error(L, "s has no field [%s]", luaL_typename(L, 2));
  const char* name = lua_tostring(L, 2);
  if (!vm->needs_velocity && std::strcmp(name, "v") == 0) {
    return luaL_error(L, "s.v is not available: the script declares needs.velocity = false");
  }
  if (!vm->needs_time && std::strcmp(name, "t") == 0) {
    return luaL_error(L, "s.t is not available: the script declares needs.time = false");
  }
  // A field of another number of axes: the script was written for a scene of another kind.
  int field = 0;
  const bool in_scene = find_state_field(name, vm->axes, &field);
  char scenes[32];
  write_scenes_with_field(name, " and ", scenes, sizeof scenes);
  if (!in_scene && scenes[0] != '\0') {
    char fields[96];
    char scripts[32];
    write_state_field_list(vm->axes, fields, sizeof fields);
    write_scenes_with_field(name, " or ", scripts, sizeof scripts);
    return luaL_error(L, "s.%s is only in %s scenes, and this is a %d-D scene (s has %s): a %s script cannot run here",
                      name, scenes, vm->axes, fields, scripts);
  }
  if (in_scene && !vm->needs_velocity && is_velocity_field(field)) {
    return luaL_error(L, "s.%s is not available: the script declares needs.velocity = false", name);
  }
  return raise_lookup_error(L, PendingSuggestion::Kind::state, "", "s has no field '%s'", name);
}

int state_newindex(lua_State* L) {
  return luaL_error(L, "s is read-only (copy the value into a local to change it)");
}

}  // namespace

// Checks the optional `needs` table (at `index`) and stores it in vm. Never raises.
bool check_needs(lua_State* L, int index, ScriptVm* vm) noexcept {
  const char* name = vm->display_name.c_str();
  if (lua_isnil(L, index)) return true;
  if (!lua_istable(L, index)) {
    set_load_error(vm, "%s: needs must be a table such as { velocity = false }, got a %s", name,
                   luaL_typename(L, index));
    return false;
  }
  // Report the alphabetically first problem, whatever Lua's table order.
  char bad_key[64] = "";
  char bad_value_key[64] = "";
  const char* bad_value_type = nullptr;
  lua_pushnil(L);
  while (lua_next(L, index) != 0) {
    const char* key = lua_type(L, -2) == LUA_TSTRING ? lua_tostring(L, -2) : "?";
    const bool known = std::strcmp(key, "velocity") == 0 || std::strcmp(key, "time") == 0;
    if (!known) {
      if (bad_key[0] == '\0' || std::strcmp(key, bad_key) < 0) {
        std::snprintf(bad_key, sizeof bad_key, "%s", key);
      }
    } else if (!lua_isboolean(L, -1)) {
      if (bad_value_key[0] == '\0' || std::strcmp(key, bad_value_key) < 0) {
        std::snprintf(bad_value_key, sizeof bad_value_key, "%s", key);
        bad_value_type = luaL_typename(L, -1);
      }
    } else if (std::strcmp(key, "velocity") == 0) {
      vm->needs_velocity = lua_toboolean(L, -1) != 0;
    } else {
      vm->needs_time = lua_toboolean(L, -1) != 0;
    }
    lua_pop(L, 1);
  }
  if (bad_key[0] != '\0') {
    const bool near_velocity = edit_distance(bad_key, "velocity") <= 3;
    const bool near_time = edit_distance(bad_key, "time") <= 2;
    set_load_error(vm, "%s: needs.%s: unknown need%s (a script can declare velocity and time)",
                   name, bad_key,
                   near_velocity ? " (did you mean \"velocity\"?)"
                   : near_time   ? " (did you mean \"time\"?)"
                                 : "");
    return false;
  }
  if (bad_value_key[0] != '\0') {
    set_load_error(vm, "%s: needs.%s: expected true or false, got a %s", name, bad_value_key,
                   bad_value_type);
    return false;
  }
  return true;
}

// Pushes the hidden data table and the proxy `s` that reads through it. The proxy is
// empty, so every read goes to the data table (whose keys the script cannot reach or
// remove), and every write to the proxy is an error.
void push_state_tables(lua_State* L, const ScriptVm* vm) {
  lua_createtable(L, 0, 2 + 2 * vm->axes);  // data
  for (int i = 0; i < vm->axes; ++i) {
    lua_pushnumber(L, 0.0);
    lua_setfield(L, -2, state_field_name(position_field(i), vm->axes));
  }
  for (int i = 0; vm->needs_velocity && i < vm->axes; ++i) {
    lua_pushnumber(L, 0.0);
    lua_setfield(L, -2, state_field_name(velocity_field(i), vm->axes));
  }
  if (vm->needs_time) {
    lua_pushnumber(L, 0.0);
    lua_setfield(L, -2, "t");
  }
  lua_pushnumber(L, 0.0);
  lua_setfield(L, -2, "dt");
  lua_createtable(L, 0, 1);
  lua_pushcfunction(L, state_index);
  lua_setfield(L, -2, "__index");
  lua_setmetatable(L, -2);

  lua_createtable(L, 0, 0);  // proxy
  lua_createtable(L, 0, 3);
  lua_pushvalue(L, -3);
  lua_setfield(L, -2, "__index");
  lua_pushcfunction(L, state_newindex);
  lua_setfield(L, -2, "__newindex");
  lua_pushboolean(L, 0);
  lua_setfield(L, -2, "__metatable");
  lua_setmetatable(L, -2);
  lua_insert(L, -2);  // proxy below data
}


}  // namespace hapscene::detail
