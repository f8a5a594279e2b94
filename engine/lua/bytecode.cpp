// Reads a function's code from lua_dump's binary chunk (Lua 5.4 format, ldump.c: a header,
// then the function's source, line range, three bytes, its code as a counted array of
// 32-bit instructions, its constants and its upvalues) and looks for jumps that go backwards. The opcode numbers are
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
// Opcodes that call a value (lopcodes.h, Lua 5.4).
constexpr unsigned kOpCall = 68;
constexpr unsigned kOpTailCall = 69;
// Opcodes whose register fields uses_first_register reads (lopcodes.h, Lua 5.4).
constexpr unsigned kOpMove = 0;
constexpr unsigned kOpGetTable = 12;
constexpr unsigned kOpGetI = 13;
constexpr unsigned kOpGetField = 14;
constexpr unsigned kOpSetTabUp = 15;
constexpr unsigned kOpSetTable = 16;
constexpr unsigned kOpSetI = 17;
constexpr unsigned kOpSetField = 18;
constexpr unsigned kOpSelf = 20;
constexpr unsigned kOpAddI = 21;   // ADDI, the K forms (ADDK .. BXORK), SHRI, SHLI: 21-33
constexpr unsigned kOpAdd = 34;    // ADD .. SHR: 34-45
constexpr unsigned kOpShr = 45;
constexpr unsigned kOpMmBin = 46;
constexpr unsigned kOpUnm = 49;    // UNM, BNOT, NOT, LEN: 49-52
constexpr unsigned kOpLen = 52;
constexpr unsigned kOpEq = 57;     // EQ, LT, LE: 57-59
constexpr unsigned kOpLe = 59;
constexpr unsigned kOpTestSet = 67;
constexpr unsigned kOpReturn = 70;
constexpr unsigned kOpClosure = 79;
constexpr unsigned kOpVararg = 80;
constexpr unsigned kOpExtraArg = 82;
constexpr unsigned kOpcodeBits = 7;

constexpr int kSignedJumpOffset = (1 << 24) - 1;  // OFFSET_sJ for a 25-bit sJ

// The header lua_dump writes on this build (LUAC_VERSION 0x54, LUAC_FORMAT 0, LUAC_DATA,
// sizes of Instruction, lua_Integer and lua_Number); LUAC_INT and LUAC_NUM follow.
constexpr char kHeader[] = "\x1bLua\x54\x00\x19\x93\r\n\x1a\n\x04\x08\x08";
constexpr std::size_t kHeaderBytes = sizeof kHeader - 1;
constexpr std::size_t kCheckNumbersBytes = 16;
// Type tags of constants in a dump (lobject.h: type | variant << 4).
constexpr unsigned kTagInteger = 3;
constexpr unsigned kTagFloat = 3 | (1 << 4);
constexpr unsigned kTagShortString = 4;
constexpr unsigned kTagLongString = 4 | (1 << 4);

// Whether an instruction only reads or computes (FunctionCode::reads_only): a list of what
// is allowed, so an opcode added or forgotten counts as a write.
bool reads_only(unsigned opcode) {
  constexpr unsigned kOpLoadNil = 8;     // MOVE, LOADI, LOADF, LOADK, LOADKX, LOADFALSE,
                                         // LFALSESKIP, LOADTRUE, LOADNIL: 0-8
  constexpr unsigned kOpGetUpval = 9;
  constexpr unsigned kOpGetTabUp = 11;   // GETTABUP, GETTABLE, GETI, GETFIELD: 11-14
  constexpr unsigned kOpMmBinK = 48;     // arithmetic 21-45, MMBIN, MMBINI, MMBINK: 21-48
  constexpr unsigned kOpGeI = 65;        // EQ .. GEI: 57-65
  constexpr unsigned kOpTest = 66;       // TEST, TESTSET: 66-67
  constexpr unsigned kOpReturn1 = 72;    // RETURN, RETURN0, RETURN1: 70-72
  return opcode <= kOpLoadNil || opcode == kOpGetUpval || (opcode >= kOpGetTabUp && opcode <= kOpGetField) ||
         (opcode >= kOpAddI && opcode <= kOpMmBinK) || (opcode >= kOpUnm && opcode <= kOpLen) ||
         opcode == kOpJmp || (opcode >= kOpEq && opcode <= kOpGeI) || opcode == kOpTest ||
         opcode == kOpTestSet || (opcode >= kOpReturn && opcode <= kOpReturn1) || opcode == kOpExtraArg;
}

int append_chunk(lua_State*, const void* bytes, std::size_t size, void* out) {
  static_cast<std::string*>(out)->append(static_cast<const char*>(bytes), size);
  return 0;
}

// A chunk being read; every read fails (returns false) past the end.
struct Reader {
  const unsigned char* at;
  const unsigned char* end;

  bool has(std::uint64_t n) const { return static_cast<std::uint64_t>(end - at) >= n; }
  bool skip(std::uint64_t n) {
    if (!has(n)) return false;
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

// Whether an instruction uses register 0 (a function's first parameter) in any way other
// than as the table of a read of a constant field (GETFIELD A 0 K): writing it, copying
// it, passing or returning it, storing it, comparing it, using it as a key or an operand.
// Errs on the side of "uses": a false answer must be exact, a true one only costs speed.
// Instruction fields (lopcodes.h, iABC): op 7 bits, A 8, k 1, B 8, C 8.
bool uses_first_register(unsigned opcode, std::uint32_t instruction) {
  const unsigned a = (instruction >> 7) & 0xffu;
  const bool k = ((instruction >> 15) & 1u) != 0;
  const unsigned b = (instruction >> 16) & 0xffu;
  const unsigned c = (instruction >> 24) & 0xffu;
  switch (opcode) {
    case kOpGetField: return a == 0;  // s.name: a read, unless it overwrites s itself
    case kOpJmp:
    case kOpExtraArg: return false;   // no register fields
    case kOpClosure: return true;     // a nested function may capture it as an upvalue
    case kOpVararg: return true;
    case kOpSetTabUp: return !k && c == 0;  // A is an upvalue; RK(C) the value stored
    default: break;
  }
  if (a == 0) return true;  // every other opcode has a register (or a range from it) in A
  // B as a register.
  const bool b_register = opcode == kOpMove || opcode == kOpGetTable || opcode == kOpGetI ||
                          opcode == kOpSetTable || opcode == kOpSelf ||
                          (opcode >= kOpAddI && opcode <= kOpShr) || opcode == kOpMmBin ||
                          (opcode >= kOpUnm && opcode <= kOpLen) || (opcode >= kOpEq && opcode <= kOpLe) ||
                          opcode == kOpTestSet;
  if (b_register && b == 0) return true;
  // C as a register, or RK(C) (a register when k is 0).
  const bool c_register = opcode == kOpGetTable || (opcode >= kOpAdd && opcode <= kOpShr);
  const bool c_rk = opcode == kOpSetTable || opcode == kOpSetI || opcode == kOpSetField || opcode == kOpSelf;
  return c == 0 && (c_register || (c_rk && !k));
}

}  // namespace

bool read_function_chunk(lua_State* L, int index, FunctionChunk* out) {
  *out = FunctionChunk{};
  if (lua_type(L, index) != LUA_TFUNCTION || lua_iscfunction(L, index)) return false;
  std::string chunk;
  lua_pushvalue(L, index);
  const int status = lua_dump(L, append_chunk, &chunk, 1);
  lua_pop(L, 1);
  if (status != 0 || chunk.size() < kHeaderBytes ||
      std::memcmp(chunk.data(), kHeader, kHeaderBytes) != 0) {
    return false;
  }
  Reader reader{reinterpret_cast<const unsigned char*>(chunk.data()),
                reinterpret_cast<const unsigned char*>(chunk.data()) + chunk.size()};
  std::uint64_t source_size = 0, line = 0, code_size = 0, constant_count = 0, upvalue_count = 0;
  if (!reader.skip(kHeaderBytes + kCheckNumbersBytes + 1)) return false;  // + number of upvalues
  if (!reader.size(&source_size)) return false;                             // 0 when stripped
  if (source_size > 0 && !reader.skip(source_size - 1)) return false;
  if (!reader.size(&line) || !reader.size(&line)) return false;             // line range
  if (static_cast<std::size_t>(reader.end - reader.at) < 3) return false;
  out->parameters = reader.at[0];
  out->vararg = reader.at[1] != 0;
  out->stack_size = reader.at[2];
  reader.skip(3);
  if (!reader.size(&code_size) || code_size == 0) return false;
  if (code_size > static_cast<std::uint64_t>(reader.end - reader.at) / 4) return false;
  out->code.resize(code_size);
  std::memcpy(out->code.data(), reader.at, 4 * code_size);  // dumped in the machine's byte order
  reader.skip(4 * code_size);

  // Constants: a type tag (lobject.h variant tags), then the value.
  if (!reader.size(&constant_count) || constant_count > static_cast<std::uint64_t>(reader.end - reader.at)) {
    return false;
  }
  out->constants.resize(constant_count);
  for (LuaConstant& constant : out->constants) {
    if (reader.at == reader.end) return false;
    const unsigned tag = *reader.at++;
    if (tag == kTagInteger || tag == kTagFloat) {
      if (!reader.has(8)) return false;
      if (tag == kTagInteger) {
        constant.kind = LuaConstant::Kind::integer;
        std::memcpy(&constant.integer, reader.at, 8);
      } else {
        constant.kind = LuaConstant::Kind::number;
        std::memcpy(&constant.number, reader.at, 8);
      }
      reader.skip(8);
    } else if (tag == kTagShortString || tag == kTagLongString) {
      std::uint64_t size = 0;
      if (!reader.size(&size) || size == 0 || !reader.has(size - 1)) return false;
      constant.kind = LuaConstant::Kind::string;
      constant.text.assign(reinterpret_cast<const char*>(reader.at), size - 1);
      reader.skip(size - 1);
    }  // nil, false, true: no value
  }
  if (!reader.size(&upvalue_count) || !reader.has(3 * upvalue_count)) return false;
  out->upvalue_count = static_cast<int>(upvalue_count);
  return true;
}

FunctionCode read_function_code(lua_State* L, int index) {
  FunctionCode code;
  FunctionChunk chunk;
  if (!read_function_chunk(L, index, &chunk)) return code;
  bool loops = false;
  bool calls = false;
  bool writes = false;
  bool first_escapes = chunk.vararg;  // `...` holds the arguments too
  for (const std::uint32_t instruction : chunk.code) {
    const unsigned opcode = instruction & ((1u << kOpcodeBits) - 1);
    if (opcode == kOpForLoop || opcode == kOpTForLoop) loops = true;
    if (opcode == kOpCall || opcode == kOpTailCall) calls = true;
    if (opcode == kOpJmp) {
      const int jump = static_cast<int>(instruction >> kOpcodeBits) - kSignedJumpOffset;
      if (jump < 0) loops = true;
    }
    if (!first_escapes && uses_first_register(opcode, instruction)) first_escapes = true;
    if (!reads_only(opcode)) writes = true;
  }
  code.calls = calls;
  code.first_parameter_read_by_field_only = !first_escapes;
  code.reads_only = !writes && !loops && !calls && !chunk.vararg;
  if (!loops) code.straight_line_length = static_cast<std::int64_t>(chunk.code.size());
  return code;
}

std::int64_t straight_line_length(lua_State* L, int index, bool* calls) {
  const FunctionCode code = read_function_code(L, index);
  if (calls != nullptr) *calls = code.straight_line_length == 0 || code.calls;
  return code.straight_line_length;
}

}  // namespace hapscene::detail
