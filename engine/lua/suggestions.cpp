// The hint of a failed lookup ("did you mean 's.x'?"): noted where the lookup fails (the
// table and the name, into buffers that exist already), searched only when the error is
// reported, outside any protected call.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string_view>

#include "engine/base/units.hpp"
#include "engine/lua/script_vm.hpp"

namespace hapscene::detail {
namespace {

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

}  // namespace

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

}  // namespace hapscene::detail
