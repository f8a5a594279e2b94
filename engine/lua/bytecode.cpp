// Reads a function's code from lua_dump's binary chunk (Lua 5.4 format: a header, then
// the function's source, line range, three bytes, and its code as a counted array of
// 32-bit instructions) and looks for jumps that go backwards. The opcode numbers are
// those of lopcodes.h, unchanged from Lua 5.4.0 to 5.4.8; a chunk from any other
// version fails the header check and is treated as "can loop".
#include "engine/lua/bytecode.hpp"

#include <cstring>
#include <string>

namespace hapscene::detail {
namespace {

// Opcodes that move the program counter backwards (lopcodes.h, Lua 5.4).
constexpr unsigned kOpJmp = 56;       // pc += sJ; backwards when sJ < 0 (loops, goto)
constexpr unsigned kOpForLoop = 73;   // numeric for: always back to the loop body
constexpr unsigned kOpTForLoop = 77;  // generic for: always back to the call
constexpr unsigned kOpcodeBits = 7;
constexpr int kSignedJumpOffset = (1 << 24) - 1;  // OFFSET_sJ for a 25-bit sJ

// The header lua_dump writes on this build (LUAC_VERSION 0x54, LUAC_FORMAT 0, LUAC_DATA,
// sizes of Instruction, lua_Integer and lua_Number); LUAC_INT and LUAC_NUM follow.
constexpr char kHeader[] = "\x1bLua\x54\x00\x19\x93\r\n\x1a\n\x04\x08\x08";
constexpr std::size_t kHeaderBytes = sizeof kHeader - 1;
constexpr std::size_t kCheckNumbersBytes = 16;

int append_chunk(lua_State*, const void* bytes, std::size_t size, void* out) {
  static_cast<std::string*>(out)->append(static_cast<const char*>(bytes), size);
  return 0;
}

// A chunk being read; every read fails (returns false) past the end.
struct Reader {
  const unsigned char* at;
  const unsigned char* end;

  bool skip(std::size_t n) {
    if (static_cast<std::size_t>(end - at) < n) return false;
    at += n;
    return true;
  }
  // dumpSize: 7 bits per byte, most significant first, the last byte marked with 0x80.
  bool size(std::uint64_t* value) {
    *value = 0;
    for (int i = 0; i < 10; ++i) {
      if (at == end) return false;
      const unsigned char byte = *at++;
      *value = (*value << 7) | (byte & 0x7fu);
      if (byte & 0x80u) return true;
    }
    return false;
  }
};

}  // namespace

std::int64_t straight_line_length(lua_State* L, int index) {
  if (lua_type(L, index) != LUA_TFUNCTION || lua_iscfunction(L, index)) return 0;
  std::string chunk;
  lua_pushvalue(L, index);
  const int status = lua_dump(L, append_chunk, &chunk, 1);
  lua_pop(L, 1);
  if (status != 0 || chunk.size() < kHeaderBytes ||
      std::memcmp(chunk.data(), kHeader, kHeaderBytes) != 0) {
    return 0;
  }
  Reader reader{reinterpret_cast<const unsigned char*>(chunk.data()),
                reinterpret_cast<const unsigned char*>(chunk.data()) + chunk.size()};
  std::uint64_t source_size = 0, line = 0, code_size = 0;
  if (!reader.skip(kHeaderBytes + kCheckNumbersBytes + 1)) return 0;  // + number of upvalues
  if (!reader.size(&source_size)) return 0;                             // 0 when stripped
  if (source_size > 0 && !reader.skip(source_size - 1)) return 0;
  if (!reader.size(&line) || !reader.size(&line)) return 0;             // line range
  if (!reader.skip(3)) return 0;                                        // params, vararg, stack
  if (!reader.size(&code_size) || code_size == 0) return 0;
  if (code_size > static_cast<std::uint64_t>(reader.end - reader.at) / 4) return 0;

  for (std::uint64_t i = 0; i < code_size; ++i) {
    std::uint32_t instruction = 0;
    std::memcpy(&instruction, reader.at + 4 * i, 4);  // dumped in the machine's byte order
    const unsigned opcode = instruction & ((1u << kOpcodeBits) - 1);
    if (opcode == kOpForLoop || opcode == kOpTForLoop) return 0;
    if (opcode == kOpJmp) {
      const int jump = static_cast<int>(instruction >> kOpcodeBits) - kSignedJumpOffset;
      if (jump < 0) return 0;
    }
  }
  return static_cast<std::int64_t>(code_size);
}

}  // namespace hapscene::detail
