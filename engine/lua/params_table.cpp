// A script's `params` table: resolved the moment the chunk assigns it (so top-level code
// already sees SI values and the JSON overrides), then sealed, so that a misspelt or new
// parameter is an error naming the nearest one.
#include <string_view>
#include <unordered_map>

#include "engine/lua/params.hpp"
#include "engine/lua/script_vm.hpp"

namespace hapscene::detail {
namespace {

// Registry key of the params table as first assigned.
const char kParamsKey = 0;

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

}  // namespace

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
  if (!resolve_declared(L, 3, where, line, vm)) return raise_tripped(L);
  write_params(L, 3, vm);
  seal_params(L, 3);
  lua_pushvalue(L, 3);
  lua_rawsetp(L, LUA_REGISTRYINDEX, &kParamsKey);
  vm->params_assigned = true;
  lua_rawset(L, 1);
  return 0;
}

bool finish_params(lua_State* L, int env, ScriptVm* vm) {
  const char* name = vm->display_name.c_str();
  lua_pushliteral(L, "params");
  lua_rawget(L, env);
  if (!vm->params_assigned) {
    if (!resolve_declared(L, 0, name, 0, vm)) return false;
    lua_newtable(L);
    seal_params(L, -1);
    lua_setfield(L, env, "params");
    return true;
  }
  lua_rawgetp(L, LUA_REGISTRYINDEX, &kParamsKey);
  if (!lua_rawequal(L, -1, -2)) {
    set_load_error(vm, "%s: params was replaced after it was declared: declare every parameter "
                       "in one params table", name);
    return false;
  }
  return true;
}

}  // namespace hapscene::detail
