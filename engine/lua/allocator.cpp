// The lua_Alloc of a sandboxed state: accounts every block (new size minus old size) and
// refuses growth past the limits. A refusal is a Lua memory error; it also trips the
// state (see budget.cpp), so the script cannot catch it with pcall and carry on.
#include <cstdlib>

#include "engine/lua/script_vm.hpp"

namespace hapscene::detail {
namespace {

// Lua 5.4 allocates a string as one block: a 24-byte header (64-bit), the text and a
// terminating zero.
constexpr std::size_t kStringHeaderBytes = 24 + 1;

// Records why the allocation was refused, with the script's position when one is known.
void refuse(ScriptVm* vm, const char* what, std::size_t limit, const char* unit) {
  if (vm->L == nullptr || vm->tripped) return;
  char where[160];
  describe_position(vm->L, 0, vm, where, sizeof where);
  // A deep stack means runaway recursion: say so, since the symptom is memory.
  lua_Debug deep{};
  const bool recursion = lua_getstack(vm->L, 1000, &deep) != 0;
  record_fault(vm, ScriptFault::memory_limit, "%s: %s (%zu %s)%s", where, what, limit, unit,
               recursion ? "; the call stack is over 1000 levels deep (runaway recursion?)" : "");
  trip(vm, vm->L);
}

// The memory cap counts garbage too. When Lua can free some, it runs an emergency
// collection and asks again with the same block and size; only a second refusal trips.
bool within_memory_cap(ScriptVm* vm, const void* block, std::size_t growth, std::size_t new_size) {
  const bool fits = vm->bytes + growth <= vm->limits.memory_bytes;
  const bool is_retry = vm->awaiting_retry && vm->retry_block == block && vm->retry_size == new_size;
  vm->awaiting_retry = false;
  if (fits) return true;
  if (is_retry) {
    refuse(vm, "memory limit exceeded", vm->limits.memory_bytes, "bytes");
  } else {
    vm->awaiting_retry = true;
    vm->retry_block = block;
    vm->retry_size = new_size;
  }
  return false;
}

}  // namespace

void* capped_alloc(void* ud, void* block, std::size_t old_size, std::size_t new_size) {
  auto* vm = static_cast<ScriptVm*>(ud);
  // When block is null, old_size is the type of the new object, not a size.
  const std::size_t old_bytes = block != nullptr ? old_size : 0;

  // Free.
  if (new_size == 0) {
    if (block != nullptr) {
      std::free(block);
      vm->bytes -= old_bytes;
    }
    return nullptr;
  }

  // Growth: check the limits before touching memory. Shrinking is never refused (Lua
  // relies on that).
  if (new_size > old_bytes) {
    const std::size_t growth = new_size - old_bytes;
    if (vm->tripped && vm->in_call) return nullptr;
    if (block == nullptr && old_size == LUA_TSTRING &&
        new_size > vm->limits.string_bytes + kStringHeaderBytes) {
      refuse(vm, "string limit exceeded", vm->limits.string_bytes, "bytes per string");
      return nullptr;
    }
    if (vm->in_call && vm->call_bytes + growth > vm->call_limit_bytes) {
      refuse(vm, "allocation limit exceeded", vm->call_limit_bytes, "bytes per call");
      return nullptr;
    }
    if (!within_memory_cap(vm, block, growth, new_size)) return nullptr;
    // While loading, the compiler runs without hooks: its allocations are where the load
    // deadline is checked (every 64th, a clock read costs about 25 ns).
    if (vm->phase == Phase::loading && vm->L != nullptr && ++vm->allocations_since_check >= 64) {
      vm->allocations_since_check = 0;
      if (!vm->tripped && time_exceeded(vm, vm->L, 0)) {
        trip(vm, vm->L);
        return nullptr;
      }
    }
  }

  void* result = std::realloc(block, new_size);
  if (result == nullptr) {
    // A failed shrink keeps the old, larger block, which is still valid.
    if (new_size <= old_bytes) return block;
    return nullptr;
  }
  if (new_size > old_bytes) {
    vm->bytes += new_size - old_bytes;
    vm->call_bytes += new_size - old_bytes;
    ++vm->allocations;
  } else {
    vm->bytes -= old_bytes - new_size;
  }
  return result;
}

}  // namespace hapscene::detail
