// What a script's names mean: strict globals, the `params` table (resolved the moment the
// chunk assigns it, so top-level code already sees SI values and overrides), the
// read-only state table `s`, and the checks run after the chunk has loaded (the `shapes`
// list's: script_shapes.cpp).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <string_view>
#include <unordered_map>

#include "engine/base/units.hpp"
#include "engine/lua/params.hpp"
#include "engine/lua/script_vm.hpp"

namespace hapscene::detail {
namespace {

// Registry key of the params table as first assigned.
const char kParamsKey = 0;

// ---- Suggestions: noted at the failed lookup, searched only when reported -------------

// Registry key of the table of the last failed lookup.
const char kSuggestTableKey = 0;

// Candidates compared at most; a table with more near-length names gets no suggestion,
// so the search is bounded and its answer does not depend on traversal order.
constexpr int kMaxCandidates = 256;

// The string key of the table at `index` nearest to `name` (ties: the smaller key), or ""
// when none is close: at most one edit per three letters (one for short names).
void nearest_key(lua_State* L, int index, std::string_view name, char* out, std::size_t size) {
  out[0] = '\0';
  if (name.size() > kMaxSuggestedNameBytes || lua_checkstack(L, 3) == 0) return;
  index = lua_absindex(L, index);
  const std::size_t threshold = std::max<std::size_t>(1, name.size() / 3) + 1;
  std::size_t best = threshold;
  int candidates = 0;
  lua_pushnil(L);
  while (lua_next(L, index) != 0) {
    if (lua_type(L, -2) == LUA_TSTRING) {
      std::size_t length = 0;
      const char* key = lua_tolstring(L, -2, &length);
      // The length difference is a lower bound of the distance.
      const std::size_t gap = length > name.size() ? length - name.size() : name.size() - length;
      if (gap < threshold && ++candidates <= kMaxCandidates) {
        const std::size_t d = edit_distance(name, std::string_view(key, length));
        if (d > 0 && length < size &&
            (d < best || (d == best && out[0] != '\0' && std::strcmp(key, out) < 0))) {
          best = d;
          std::memcpy(out, key, length + 1);
        }
      }
    }
    lua_pop(L, 1);
  }
  if (candidates > kMaxCandidates) out[0] = '\0';
}

// Raises "<place>: <format with name>" after noting the lookup for suggestion_for. The
// table looked up is argument 1.
int raise_lookup_error(lua_State* L, PendingSuggestion::Kind kind, const char* library,
                       const char* format, const char* name) {
  ScriptVm* vm = vm_of(L);
  luaL_where(L, 1);
  lua_pushfstring(L, format, name);
  lua_concat(L, 2);
  std::size_t length = 0;
  const char* message = lua_tolstring(L, -1, &length);
  PendingSuggestion& pending = vm->suggestion;
  pending.kind = PendingSuggestion::Kind::none;
  const std::size_t name_length = std::strlen(name);
  if (length < sizeof pending.message && name_length < sizeof pending.name) {
    std::memcpy(pending.message, message, length + 1);
    std::memcpy(pending.name, name, name_length + 1);
    std::snprintf(pending.library, sizeof pending.library, "%s", library);
    pending.kind = kind;
    lua_pushvalue(L, 1);
    lua_rawsetp(L, LUA_REGISTRYINDEX, &kSuggestTableKey);  // the slot exists: no allocation
  }
  return lua_error(L);
}

// ---- Load errors: stored as text, thrown as InputError once the Lua call returns -----

// Raises any error; the caller of the load step reads vm->load_error first.
int raise_load_error(lua_State* L) { return raise_tripped(L); }

// ---- params ------------------------------------------------------------------------

// For every name written as `name = ` at or before `last_line`, the last line where it
// is (a table constructor ends at the line of the assignment, so its fields are above
// it). One pass over the source, however many params there are.
std::unordered_map<std::string_view, int> declaration_lines(const std::string& source, int last_line) {
  std::unordered_map<std::string_view, int> lines;
  const auto is_word = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  int line = 1;
  for (std::size_t i = 0; i < source.size() && line <= last_line;) {
    if (source[i] == '\n') {
      ++line;
      ++i;
      continue;
    }
    if (!is_word(source[i])) {
      ++i;
      continue;
    }
    std::size_t end = i;
    while (end < source.size() && is_word(source[end])) ++end;
    std::size_t j = end;
    while (j < source.size() && (source[j] == ' ' || source[j] == '\t')) ++j;
    if (j < source.size() && source[j] == '=' && (j + 1 >= source.size() || source[j + 1] != '=')) {
      lines[std::string_view(source).substr(i, end - i)] = line;
    }
    i = end;
  }
  return lines;
}

// Reads the declared defaults of the table at `index` (0: none declared) and resolves
// them with the JSON overrides into vm->params. C++ only; never raises a Lua error.
bool resolve_declared(lua_State* L, int index, const char* declared_at, int assigned_line,
                      ScriptVm* vm) noexcept {
  try {
    std::vector<DeclaredParam> declared;
    std::unordered_map<std::string_view, int> lines;
    if (index != 0 && vm->source != nullptr) lines = declaration_lines(*vm->source, assigned_line);
    if (index != 0) {
      lua_pushnil(L);
      while (lua_next(L, index) != 0) {
        DeclaredParam d;
        if (lua_type(L, -2) == LUA_TSTRING) {
          d.name = lua_tostring(L, -2);
        } else if (lua_type(L, -2) == LUA_TNUMBER) {
          char key[64];
          std::snprintf(key, sizeof key, "%.14g", lua_tonumber(L, -2));
          d.key_text = key;
        } else {
          d.key_text = luaL_typename(L, -2);
        }
        switch (lua_type(L, -1)) {
          case LUA_TNUMBER:
            d.type = DeclaredParam::Type::number;
            d.number = lua_tonumber(L, -1);
            break;
          case LUA_TBOOLEAN:
            d.type = DeclaredParam::Type::boolean;
            d.boolean = lua_toboolean(L, -1) != 0;
            break;
          case LUA_TSTRING:
            d.type = DeclaredParam::Type::string;
            d.text = lua_tostring(L, -1);
            break;
          default:
            d.type = DeclaredParam::Type::other;
            d.text = luaL_typename(L, -1);
            break;
        }
        if (const auto line = lines.find(d.name); !d.name.empty() && line != lines.end()) {
          d.declared_at = vm->short_source + ":" + std::to_string(line->second);
        }
        declared.push_back(std::move(d));
        lua_pop(L, 1);
      }
    }
    static const nlohmann::json kNoOverrides = nlohmann::json::object();
    const ParamPlaces places{vm->display_name, declared_at, vm->error_context, vm->pointer_prefix};
    vm->params = resolve_params(std::move(declared),
                                vm->params_override ? *vm->params_override : kNoOverrides, places);
    return true;
  } catch (const std::exception& e) {
    set_load_error(vm, "%s", e.what());
  } catch (...) {
    set_load_error(vm, "%s: cannot resolve params", vm->display_name.c_str());
  }
  return false;
}

// params.stifness (a typo) is an error naming the nearest parameter.
int params_index(lua_State* L) {
  if (lua_type(L, 2) != LUA_TSTRING) return luaL_error(L, "params has no field [%s]", luaL_typename(L, 2));
  return raise_lookup_error(L, PendingSuggestion::Kind::params, "", "params has no field '%s'",
                            lua_tostring(L, 2));
}

// New fields of params are errors too: every parameter is declared in the table.
int params_newindex(lua_State* L) {
  return luaL_error(L, "params.%s is not declared: declare every parameter in the params table",
                    lua_type(L, 2) == LUA_TSTRING ? lua_tostring(L, 2) : "?");
}

// Hides the table's metatable and makes unknown fields errors.
void seal_params(lua_State* L, int index) { set_guard_metatable(L, index, params_index, params_newindex); }

// Writes vm->params (SI values) into the table at `index`.
void write_params(lua_State* L, int index, const ScriptVm* vm) {
  index = lua_absindex(L, index);
  for (const ScriptParam& p : vm->params) {
    lua_pushlstring(L, p.name.data(), p.name.size());
    switch (p.kind) {
      case ScriptParam::Kind::number: lua_pushnumber(L, p.value_si); break;
      case ScriptParam::Kind::boolean: lua_pushboolean(L, p.flag ? 1 : 0); break;
      case ScriptParam::Kind::text: lua_pushlstring(L, p.text.data(), p.text.size()); break;
    }
    lua_rawset(L, index);
  }
}

// `params = { ... }` at load time (stack: env, "params", table): resolve, write SI
// values back, seal, and store.
int assign_params(lua_State* L) {
  ScriptVm* vm = vm_of(L);
  if (!lua_istable(L, 3)) {
    return luaL_error(L, "params must be a table of defaults such as { stiffness = \"100 N/m\" }, "
                         "got a %s", luaL_typename(L, 3));
  }
  if (vm->params_assigned) {
    return luaL_error(L, "params is declared twice: declare every parameter in one params table");
  }
  char where[160];
  describe_position(L, 1, vm, where, sizeof where);
  lua_Debug ar{};
  const int line = lua_getstack(L, 1, &ar) != 0 && lua_getinfo(L, "l", &ar) != 0 ? ar.currentline : 0;
  if (!resolve_declared(L, 3, where, line, vm)) return raise_load_error(L);
  write_params(L, 3, vm);
  seal_params(L, 3);
  lua_pushvalue(L, 3);
  lua_rawsetp(L, LUA_REGISTRYINDEX, &kParamsKey);
  vm->params_assigned = true;
  lua_rawset(L, 1);
  return 0;
}

// ---- needs ---------------------------------------------------------------------------

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

// ---- s: the read-only state table --------------------------------------------------

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

}  // namespace

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

void prepare_suggestions(lua_State* L) {
  lua_pushboolean(L, 0);
  lua_rawsetp(L, LUA_REGISTRYINDEX, &kSuggestTableKey);
}

void suggestion_for(ScriptVm* vm, lua_State* L, const char* message, char* out, std::size_t size) {
  out[0] = '\0';
  PendingSuggestion& pending = vm->suggestion;
  if (pending.kind == PendingSuggestion::Kind::none || std::strcmp(message, pending.message) != 0) {
    return;
  }
  char nearest[64] = "";
  if (lua_checkstack(L, 4) != 0 && lua_rawgetp(L, LUA_REGISTRYINDEX, &kSuggestTableKey) == LUA_TTABLE) {
    nearest_key(L, -1, pending.name, nearest, sizeof nearest);
  }
  lua_pop(L, 1);
  const bool found = nearest[0] != '\0';
  switch (pending.kind) {
    case PendingSuggestion::Kind::state:
      if (found) {
        std::snprintf(out, size, " (did you mean 's.%s'?)", nearest);
      } else {
        char fields[96];
        write_state_field_list(vm->axes, fields, sizeof fields);
        std::snprintf(out, size, " (s has %s)", fields);
      }
      break;
    case PendingSuggestion::Kind::library:
      if (found) std::snprintf(out, size, " (did you mean '%s.%s'?)", pending.library, nearest);
      break;
    default:
      if (found) std::snprintf(out, size, " (did you mean '%s'?)", nearest);
      break;
  }
  pending.kind = PendingSuggestion::Kind::none;
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
    return raise_load_error(L);
  }
  if (!lua_isfunction(L, 2)) {
    set_load_error(vm, "%s: force must be a function, got a %s", name, luaL_typename(L, 2));
    return raise_load_error(L);
  }

  // reset (3), optional.
  lua_pushliteral(L, "reset");
  lua_rawget(L, env);
  if (!lua_isnil(L, 3) && !lua_isfunction(L, 3)) {
    set_load_error(vm, "%s: reset must be a function, got a %s", name, luaL_typename(L, 3));
    return raise_load_error(L);
  }

  // needs, optional.
  lua_pushliteral(L, "needs");
  lua_rawget(L, env);
  if (!check_needs(L, 4, vm)) return raise_load_error(L);
  lua_settop(L, 3);

  // shapes, optional (2-D scripts: compile_script refuses them in a 1-D scene).
  lua_pushliteral(L, "shapes");
  lua_rawget(L, env);
  if (!check_shapes(L, 4, vm)) return raise_load_error(L);
  lua_settop(L, 3);

  // params: a script without one gets an empty sealed table (and overrides are errors);
  // one that replaced its table after declaring it is told to use one table.
  lua_pushliteral(L, "params");
  lua_rawget(L, env);
  if (!vm->params_assigned) {
    if (!resolve_declared(L, 0, name, 0, vm)) return raise_load_error(L);
    lua_newtable(L);
    seal_params(L, -1);
    lua_setfield(L, env, "params");
  } else {
    lua_rawgetp(L, LUA_REGISTRYINDEX, &kParamsKey);
    if (!lua_rawequal(L, -1, -2)) {
      set_load_error(vm, "%s: params was replaced after it was declared: declare every parameter "
                         "in one params table", name);
      return raise_load_error(L);
    }
  }
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
