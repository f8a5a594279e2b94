// The optional `shapes` list of a 2-D script, checked once the chunk has loaded
// (finish_load, globals.cpp).
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string_view>

#include "engine/base/units.hpp"
#include "engine/lua/script_vm.hpp"

namespace hapscene::detail {
namespace {

// The optional `shapes` list of a 2-D script: boxes and circles in SI (or unit strings),
// read with raw accesses (no script code runs) into vm->shapes. The first bad entry is a
// load error naming it, "scripts/x.lua: shapes[2].radius: ...". No C++ object with a
// destructor is alive across a Lua call here (pushing a key may raise a memory error).

constexpr const char* kShapeForms =
    "{type = \"box\", min = {x, y}, max = {x, y}, solid = \"inside\"} or "
    "{type = \"circle\", center = {x, y}, radius = r, solid = \"outside\"}";

bool shape_error(ScriptVm* vm, const char* path, const char* why) {
  set_load_error(vm, "%s: %s: %s", vm->display_name.c_str(), path, why);
  return false;
}

// A string as a length (C++ only: no Lua call inside).
bool parse_length_text(const char* text, std::size_t length, double* out_m, char* why, std::size_t size) noexcept {
  try {
    const QuantityParse q = parse_quantity_as(std::string_view(text, length), Quantity::length_m);
    if (!q.ok) {
      std::snprintf(why, size, "%s", q.error.c_str());
      return false;
    }
    *out_m = q.value_si;
    return true;
  } catch (...) {
    std::snprintf(why, size, "cannot read \"%.40s\" as a length", text);
    return false;
  }
}

// The length at `index` (a number in m or a string such as "10 mm") into *out_m.
bool read_shape_length(lua_State* L, int index, ScriptVm* vm, const char* path, double* out_m) {
  char why[256];
  if (lua_type(L, index) == LUA_TNUMBER) {
    *out_m = lua_tonumber(L, index);
    if (std::isfinite(*out_m)) return true;
    std::snprintf(why, sizeof why, "expected a finite length, got %g", *out_m);
    return shape_error(vm, path, why);
  }
  if (lua_type(L, index) == LUA_TSTRING) {
    std::size_t length = 0;
    const char* text = lua_tolstring(L, index, &length);
    if (parse_length_text(text, length, out_m, why, sizeof why)) return true;
    return shape_error(vm, path, why);
  }
  std::snprintf(why, sizeof why, "expected a length (a number in m or a string such as \"10 mm\"), got a %s",
                luaL_typename(L, index));
  return shape_error(vm, path, why);
}

// The point {x, y} at `index` (two lengths) into out_m.
bool read_shape_point(lua_State* L, int index, ScriptVm* vm, const char* path, double out_m[2]) {
  char why[256];
  if (!lua_istable(L, index)) {
    std::snprintf(why, sizeof why, "expected a point {x, y} of two lengths, got a %s", luaL_typename(L, index));
    return shape_error(vm, path, why);
  }
  index = lua_absindex(L, index);
  int keys = 0;
  lua_pushnil(L);
  while (lua_next(L, index) != 0) {
    ++keys;
    lua_pop(L, 1);
  }
  if (keys != 2 || lua_rawlen(L, index) != 2) {
    std::snprintf(why, sizeof why, "expected a point {x, y} of two lengths, got a table of %d entries", keys);
    return shape_error(vm, path, why);
  }
  for (int k = 0; k < 2; ++k) {
    char component[96];
    std::snprintf(component, sizeof component, "%s[%d]", path, k + 1);
    lua_rawgeti(L, index, k + 1);
    const bool ok = read_shape_length(L, -1, vm, component, &out_m[k]);
    lua_pop(L, 1);
    if (!ok) return false;
  }
  return true;
}

// Pushes entry[key] (raw), for the field named `key`.
void push_field(lua_State* L, int index, const char* key) {
  lua_pushstring(L, key);
  lua_rawget(L, index);
}

// One entry of `shapes` (at `index`, number `number` counting from 1) into *shape.
bool read_shape(lua_State* L, int index, int number, ScriptVm* vm, ScriptShape* shape) {
  char path[64];
  char field[96];
  char why[512];
  std::snprintf(path, sizeof path, "shapes[%d]", number);
  if (!lua_istable(L, index)) {
    std::snprintf(why, sizeof why, "expected a table such as %s, got a %s", kShapeForms, luaL_typename(L, index));
    return shape_error(vm, path, why);
  }
  index = lua_absindex(L, index);

  // type, which says what the other keys are.
  std::snprintf(field, sizeof field, "%s.type", path);
  push_field(L, index, "type");
  const bool named = lua_type(L, -1) == LUA_TSTRING;
  const char* type = named ? lua_tostring(L, -1) : luaL_typename(L, -1);
  const bool box = named && std::strcmp(type, "box") == 0;
  const bool circle = named && std::strcmp(type, "circle") == 0;
  if (!box && !circle) {
    if (named) {
      std::snprintf(why, sizeof why, "expected \"box\" or \"circle\", got \"%.40s\"", type);
    } else {
      std::snprintf(why, sizeof why, "expected \"box\" or \"circle\", got a %s", type);
    }
    lua_pop(L, 1);
    return shape_error(vm, field, why);
  }
  lua_pop(L, 1);
  type = box ? "box" : "circle";  // the messages below name the kind, not the popped string
  shape->kind = box ? ScriptShape::Kind::box : ScriptShape::Kind::circle;
  static constexpr const char* kBoxKeys[] = {"type", "min", "max", "solid"};
  static constexpr const char* kCircleKeys[] = {"type", "center", "radius", "solid"};
  const char* const* keys = box ? kBoxKeys : kCircleKeys;
  const char* key_list = box ? "type, min, max, solid" : "type, center, radius, solid";

  // Unknown keys: the alphabetically first, whatever Lua's table order.
  char bad_key[64] = "";
  bool bad_key_type = false;
  lua_pushnil(L);
  while (lua_next(L, index) != 0) {
    if (lua_type(L, -2) != LUA_TSTRING) {
      bad_key_type = true;
    } else {
      const char* key = lua_tostring(L, -2);
      bool known = false;
      for (int k = 0; k < 4; ++k) known = known || std::strcmp(key, keys[k]) == 0;
      if (!known && (bad_key[0] == '\0' || std::strcmp(key, bad_key) < 0)) std::snprintf(bad_key, sizeof bad_key, "%s", key);
    }
    lua_pop(L, 1);
  }
  if (bad_key_type) {
    std::snprintf(why, sizeof why, "a %s's keys are names (%s), and this one has a key that is not", type, key_list);
    return shape_error(vm, path, why);
  }
  if (bad_key[0] != '\0') {
    const char* nearest = "";
    std::size_t best = 3;
    for (int k = 0; k < 4; ++k) {
      const std::size_t d = edit_distance(bad_key, keys[k]);
      if (d < best) {
        best = d;
        nearest = keys[k];
      }
    }
    std::snprintf(field, sizeof field, "%s.%s", path, bad_key);
    std::snprintf(why, sizeof why, "not a key of a %s (it takes %s)%s%s%s", type, key_list,
                  nearest[0] != '\0' ? " (did you mean \"" : "", nearest, nearest[0] != '\0' ? "\"?)" : "");
    return shape_error(vm, field, why);
  }

  // solid, required as for the built-in shapes.
  std::snprintf(field, sizeof field, "%s.solid", path);
  push_field(L, index, "solid");
  const bool solid_named = lua_type(L, -1) == LUA_TSTRING;
  const char* solid = solid_named ? lua_tostring(L, -1) : luaL_typename(L, -1);
  const bool inside = solid_named && std::strcmp(solid, "inside") == 0;
  const bool outside = solid_named && std::strcmp(solid, "outside") == 0;
  if (!inside && !outside) {
    if (solid_named) {
      std::snprintf(why, sizeof why, "expected \"inside\" (the %s is solid) or \"outside\" (a cage), got \"%.40s\"",
                    box ? "box" : "circle", solid);
    } else {
      std::snprintf(why, sizeof why, "expected \"inside\" (the %s is solid) or \"outside\" (a cage), got a %s",
                    box ? "box" : "circle", solid);
    }
    lua_pop(L, 1);
    return shape_error(vm, field, why);
  }
  lua_pop(L, 1);
  shape->solid_inside = inside;

  if (box) {
    for (const bool upper : {false, true}) {
      std::snprintf(field, sizeof field, "%s.%s", path, upper ? "max" : "min");
      push_field(L, index, upper ? "max" : "min");
      const bool ok = read_shape_point(L, -1, vm, field, upper ? shape->max_m : shape->min_m);
      lua_pop(L, 1);
      if (!ok) return false;
    }
    if (!(shape->min_m[0] < shape->max_m[0] && shape->min_m[1] < shape->max_m[1])) {
      std::snprintf(why, sizeof why, "need min < max in x and in y, got min (%g, %g) mm, max (%g, %g) mm",
                    shape->min_m[0] * 1e3, shape->min_m[1] * 1e3, shape->max_m[0] * 1e3, shape->max_m[1] * 1e3);
      return shape_error(vm, path, why);
    }
  } else {
    std::snprintf(field, sizeof field, "%s.center", path);
    push_field(L, index, "center");
    bool ok = read_shape_point(L, -1, vm, field, shape->center_m);
    lua_pop(L, 1);
    if (!ok) return false;
    std::snprintf(field, sizeof field, "%s.radius", path);
    push_field(L, index, "radius");
    ok = read_shape_length(L, -1, vm, field, &shape->radius_m);
    lua_pop(L, 1);
    if (!ok) return false;
    if (!(shape->radius_m > 0.0)) {
      std::snprintf(why, sizeof why, "expected a radius above 0, got %g mm", shape->radius_m * 1e3);
      return shape_error(vm, field, why);
    }
  }
  return true;
}

bool append_shape(ScriptVm* vm, const ScriptShape& shape) noexcept {
  try {
    vm->shapes.push_back(shape);
    return true;
  } catch (...) {
    set_load_error(vm, "%s: shapes: out of memory", vm->display_name.c_str());
    return false;
  }
}

}  // namespace

// Checks the optional `shapes` list (at `index`) and stores it in vm->shapes.
bool check_shapes(lua_State* L, int index, ScriptVm* vm) {
  const char* name = vm->display_name.c_str();
  if (lua_isnil(L, index)) return true;
  if (!lua_istable(L, index)) {
    set_load_error(vm, "%s: shapes must be a list such as { %s }, got a %s", name, kShapeForms,
                   luaL_typename(L, index));
    return false;
  }
  index = lua_absindex(L, index);
  std::size_t keys = 0;
  lua_pushnil(L);
  while (lua_next(L, index) != 0) {
    ++keys;
    lua_pop(L, 1);
  }
  const std::size_t count = lua_rawlen(L, index);
  if (keys != count) {
    set_load_error(vm, "%s: shapes must be a list { shape, shape, ... } (keys 1 to n), and it has other keys", name);
    return false;
  }
  if (count > kMaxScriptShapes) {
    set_load_error(vm, "%s: shapes has %zu entries; a script may declare at most %zu", name, count, kMaxScriptShapes);
    return false;
  }
  for (std::size_t i = 1; i <= count; ++i) {
    lua_rawgeti(L, index, static_cast<lua_Integer>(i));
    ScriptShape shape;
    const bool ok = read_shape(L, -1, static_cast<int>(i), vm, &shape);
    lua_pop(L, 1);
    if (!ok || !append_shape(vm, shape)) return false;
  }
  return true;
}

}  // namespace hapscene::detail
