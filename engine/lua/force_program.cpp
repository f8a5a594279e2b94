// The translation reads the bytecode once, in order. Lua 5.4 jumps of a straight-line
// function only go forward, so every instruction's predecessors come before it: one pass
// finds, for each reachable instruction, what each register holds (nothing, s, an
// integer or a float) and refuses the function at the first instruction outside the
// supported set or the first read of a register that may hold anything but a number.
// Opcode numbers and instruction fields are those of lopcodes.h, unchanged from Lua
// 5.4.0 to 5.4.8; the semantics reproduced are lvm.c's and llimits.h's.
#include "engine/lua/force_program.hpp"

#include <cmath>
#include <cstring>
#include <string_view>
#include <utility>

namespace hapscene::detail {
namespace {

// Opcodes (lopcodes.h, Lua 5.4).
enum Opcode : unsigned {
  kMove = 0, kLoadI = 1, kLoadF = 2, kLoadK = 3,
  kGetUpval = 9, kGetField = 14,
  kAddI = 21, kAddK = 22, kSubK = 23, kMulK = 24, kModK = 25, kPowK = 26, kDivK = 27, kIDivK = 28,
  kAdd = 34, kSub = 35, kMul = 36, kMod = 37, kPow = 38, kDiv = 39, kIDiv = 40,
  kMmBin = 46, kMmBinI = 47, kMmBinK = 48,
  kUnm = 49, kJmp = 56,
  kEq = 57, kLt = 58, kLe = 59, kEqK = 60, kEqI = 61, kLtI = 62, kLeI = 63, kGtI = 64, kGeI = 65,
  kReturn = 70, kReturn0 = 71, kReturn1 = 72,
};

// Instruction fields (lopcodes.h): op 7 bits, A 8, k 1, B 8, C 8; Bx and sBx 17; sJ 25.
unsigned op_of(std::uint32_t i) { return i & 0x7fu; }
unsigned a_of(std::uint32_t i) { return (i >> 7) & 0xffu; }
bool k_of(std::uint32_t i) { return ((i >> 15) & 1u) != 0; }
unsigned b_of(std::uint32_t i) { return (i >> 16) & 0xffu; }
unsigned c_of(std::uint32_t i) { return (i >> 24) & 0xffu; }
unsigned bx_of(std::uint32_t i) { return i >> 15; }
int sbx_of(std::uint32_t i) { return static_cast<int>(bx_of(i)) - 65535; }
int sb_of(std::uint32_t i) { return static_cast<int>(b_of(i)) - 127; }
int sc_of(std::uint32_t i) { return static_cast<int>(c_of(i)) - 127; }
int sj_of(std::uint32_t i) { return static_cast<int>(i >> 7) - 16777215; }

// What a register holds at an instruction. `none`: nothing usable (never written, nil, or
// different things on different paths).
enum class Holds : std::uint8_t { unreached, none, state, integer, number };

Holds merge(Holds into, Holds from) {
  if (into == Holds::unreached) return from;
  return into == from ? into : Holds::none;
}

// Integers beyond 2^53 do not convert to doubles exactly; a comparison or an operation
// with one would differ from Lua's.
constexpr double kExactIntegerLimit = 9007199254740992.0;

}  // namespace

std::optional<ForceProgram> ForceProgram::translate(const FunctionChunk& chunk,
                                                    const std::array<bool, kFieldCount>& present, lua_State* L,
                                                    int function_index) {
  const int count = static_cast<int>(chunk.code.size());
  const int registers = chunk.stack_size;
  if (chunk.vararg || chunk.parameters < 1 || count == 0 || count > 1024 || registers < 1) return std::nullopt;

  ForceProgram program;
  program.values_.assign(static_cast<std::size_t>(registers), 0.0);
  const auto add_value = [&](double value) {
    program.values_.push_back(value);
    return static_cast<int>(program.values_.size()) - 1;
  };
  for (int f = 0; f < kFieldCount; ++f) program.field_slot_[f] = add_value(0.0);
  static constexpr std::string_view kFieldNames[kFieldCount] = {"x", "v", "t", "dt", "y", "vx", "vy"};

  // Upvalues this function reads: their values now, as numbers.
  std::vector<int> upvalue_slot(static_cast<std::size_t>(chunk.upvalue_count), -1);
  std::vector<Holds> upvalue_holds(static_cast<std::size_t>(chunk.upvalue_count), Holds::none);
  const int function = lua_absindex(L, function_index);
  for (int u = 0; u < chunk.upvalue_count; ++u) {
    if (lua_getupvalue(L, function, u + 1) == nullptr) return std::nullopt;
    if (lua_type(L, -1) == LUA_TNUMBER) {
      const bool integer = lua_isinteger(L, -1) != 0;
      const double value = lua_tonumber(L, -1);
      if (!integer || std::fabs(value) <= kExactIntegerLimit) {
        upvalue_holds[static_cast<std::size_t>(u)] = integer ? Holds::integer : Holds::number;
        upvalue_slot[static_cast<std::size_t>(u)] = -2;  // slot made when first read
      }
    }
    lua_pop(L, 1);
  }

  // Pass 1: what each register holds at each reachable instruction.
  std::vector<std::vector<Holds>> holds(static_cast<std::size_t>(count) + 1,
                                        std::vector<Holds>(static_cast<std::size_t>(registers), Holds::unreached));
  std::vector<bool> reached(static_cast<std::size_t>(count) + 1, false);
  reached[0] = true;
  for (int r = 0; r < registers; ++r) holds[0][static_cast<std::size_t>(r)] = r == 0 ? Holds::state : Holds::none;

  const auto constant_holds = [&](unsigned index) {
    if (index >= chunk.constants.size()) return Holds::none;
    const LuaConstant& k = chunk.constants[index];
    if (k.kind == LuaConstant::Kind::number) return Holds::number;
    if (k.kind == LuaConstant::Kind::integer &&
        std::fabs(static_cast<double>(k.integer)) <= kExactIntegerLimit) {
      return Holds::integer;
    }
    return Holds::none;
  };
  const auto constant_value = [&](unsigned index) {
    const LuaConstant& k = chunk.constants[index];
    return k.kind == LuaConstant::Kind::number ? k.number : static_cast<double>(k.integer);
  };
  const auto is_number = [](Holds h) { return h == Holds::integer || h == Holds::number; };
  const auto flow = [&](int to, const std::vector<Holds>& state) {
    if (to < 0 || to > count) return false;
    auto& into = holds[static_cast<std::size_t>(to)];
    for (std::size_t r = 0; r < into.size(); ++r) into[r] = merge(into[r], state[r]);
    reached[static_cast<std::size_t>(to)] = true;
    return true;
  };
  // After an arithmetic instruction Lua skips the MMBIN that follows (it only runs when
  // an operand is not a number).
  const auto after_arithmetic = [&](int pc) {
    const bool mm = pc + 1 < count && (op_of(chunk.code[static_cast<std::size_t>(pc + 1)]) == kMmBin ||
                                       op_of(chunk.code[static_cast<std::size_t>(pc + 1)]) == kMmBinI ||
                                       op_of(chunk.code[static_cast<std::size_t>(pc + 1)]) == kMmBinK);
    return mm ? pc + 2 : pc + 1;
  };
  // Lua's integer arithmetic applies when both operands are integers, except for / and ^.
  const auto arithmetic_result = [](unsigned op, Holds left, Holds right) {
    const bool float_only = op == kDiv || op == kDivK || op == kPow || op == kPowK;
    if (left == Holds::integer && right == Holds::integer && !float_only) return Holds::none;
    return Holds::number;
  };

  for (int pc = 0; pc < count; ++pc) {
    if (!reached[static_cast<std::size_t>(pc)]) continue;
    const std::uint32_t i = chunk.code[static_cast<std::size_t>(pc)];
    std::vector<Holds> state = holds[static_cast<std::size_t>(pc)];
    const auto reg = [&](unsigned r) { return r < static_cast<unsigned>(registers) ? state[r] : Holds::none; };
    const unsigned a = a_of(i);
    if (a >= static_cast<unsigned>(registers) && op_of(i) != kJmp) return std::nullopt;
    switch (op_of(i)) {
      case kMove:
        if (!is_number(reg(b_of(i)))) return std::nullopt;
        state[a] = reg(b_of(i));
        flow(pc + 1, state);
        break;
      case kLoadI: state[a] = Holds::integer; flow(pc + 1, state); break;
      case kLoadF: state[a] = Holds::number; flow(pc + 1, state); break;
      case kLoadK: {
        const Holds h = constant_holds(bx_of(i));
        if (!is_number(h)) return std::nullopt;
        state[a] = h;
        flow(pc + 1, state);
        break;
      }
      case kGetUpval: {
        const unsigned u = b_of(i);
        if (u >= upvalue_holds.size() || !is_number(upvalue_holds[u])) return std::nullopt;
        state[a] = upvalue_holds[u];
        flow(pc + 1, state);
        break;
      }
      case kGetField: {
        if (reg(b_of(i)) != Holds::state || c_of(i) >= chunk.constants.size()) return std::nullopt;
        const LuaConstant& key = chunk.constants[c_of(i)];
        if (key.kind != LuaConstant::Kind::string) return std::nullopt;
        bool known = false;
        for (int f = 0; f < kFieldCount; ++f) known = known || (present[f] && key.text == kFieldNames[f]);
        if (!known) return std::nullopt;  // Lua raises "s has no field ...": the VM says so
        state[a] = Holds::number;
        flow(pc + 1, state);
        break;
      }
      case kAddI: {
        const Holds r = arithmetic_result(kAdd, reg(b_of(i)), Holds::integer);
        if (!is_number(reg(b_of(i))) || r == Holds::none) return std::nullopt;
        state[a] = r;
        flow(after_arithmetic(pc), state);
        break;
      }
      case kAddK: case kSubK: case kMulK: case kModK: case kPowK: case kDivK: case kIDivK: {
        const Holds k = constant_holds(c_of(i));
        if (!is_number(reg(b_of(i))) || !is_number(k)) return std::nullopt;
        const Holds r = arithmetic_result(op_of(i), reg(b_of(i)), k);
        if (r == Holds::none) return std::nullopt;
        state[a] = r;
        flow(after_arithmetic(pc), state);
        break;
      }
      case kAdd: case kSub: case kMul: case kMod: case kPow: case kDiv: case kIDiv: {
        if (!is_number(reg(b_of(i))) || !is_number(reg(c_of(i)))) return std::nullopt;
        const Holds r = arithmetic_result(op_of(i), reg(b_of(i)), reg(c_of(i)));
        if (r == Holds::none) return std::nullopt;
        state[a] = r;
        flow(after_arithmetic(pc), state);
        break;
      }
      case kUnm:
        // -integer stays an integer, exact as a double within 2^53 (the only integers here).
        if (!is_number(reg(b_of(i)))) return std::nullopt;
        state[a] = reg(b_of(i));
        flow(pc + 1, state);
        break;
      case kJmp:
        if (sj_of(i) < 0 || !flow(pc + 1 + sj_of(i), state)) return std::nullopt;
        break;
      case kEq: case kLt: case kLe:
        if (!is_number(reg(a)) || !is_number(reg(b_of(i)))) return std::nullopt;
        if (pc + 1 >= count || op_of(chunk.code[static_cast<std::size_t>(pc + 1)]) != kJmp) return std::nullopt;
        flow(pc + 1, state);
        flow(pc + 2, state);
        break;
      case kEqK:
        if (!is_number(reg(a)) || !is_number(constant_holds(b_of(i)))) return std::nullopt;
        if (pc + 1 >= count || op_of(chunk.code[static_cast<std::size_t>(pc + 1)]) != kJmp) return std::nullopt;
        flow(pc + 1, state);
        flow(pc + 2, state);
        break;
      case kEqI: case kLtI: case kLeI: case kGtI: case kGeI:
        if (!is_number(reg(a))) return std::nullopt;
        if (pc + 1 >= count || op_of(chunk.code[static_cast<std::size_t>(pc + 1)]) != kJmp) return std::nullopt;
        flow(pc + 1, state);
        flow(pc + 2, state);
        break;
      case kReturn: {
        const unsigned b = b_of(i);
        if (b == 0) return std::nullopt;  // as many values as on the stack
        for (unsigned r = a; r + 1 < a + b; ++r) {
          if (!is_number(reg(r))) return std::nullopt;
        }
        break;
      }
      case kReturn0: break;
      case kReturn1:
        if (!is_number(reg(a))) return std::nullopt;
        break;
      default: return std::nullopt;
    }
  }

  if (reached[static_cast<std::size_t>(count)]) return std::nullopt;  // runs off the end

  // Pass 2: one op per reachable instruction (MMBINs are never reached).
  std::vector<int> op_index(static_cast<std::size_t>(count) + 1, -1);
  int next = 0;
  for (int pc = 0; pc < count; ++pc) {
    if (reached[static_cast<std::size_t>(pc)]) op_index[static_cast<std::size_t>(pc)] = next++;
  }
  const auto constant_slot = [&](double value) {
    for (std::size_t s = static_cast<std::size_t>(registers); s < program.values_.size(); ++s) {
      // Same bits (so 0.0 and -0.0 stay apart), and not a field or upvalue slot.
      bool is_constant = true;
      for (int f = 0; f < kFieldCount; ++f) is_constant = is_constant && program.field_slot_[f] != static_cast<int>(s);
      for (const Upvalue& u : program.upvalues_) is_constant = is_constant && u.slot != static_cast<int>(s);
      if (is_constant && std::memcmp(&program.values_[s], &value, sizeof value) == 0) return static_cast<int>(s);
    }
    return add_value(value);
  };
  const auto upvalue_value_slot = [&](unsigned u) {
    if (upvalue_slot[u] < 0) {
      upvalue_slot[u] = add_value(0.0);
      program.upvalues_.push_back({static_cast<int>(u) + 1, upvalue_slot[u], upvalue_holds[u] == Holds::integer});
    }
    return upvalue_slot[u];
  };
  const auto field_value_slot = [&](const std::string& name) {
    for (int f = 0; f < kFieldCount; ++f) {
      if (name == kFieldNames[f]) return program.field_slot_[f];
    }
    return -1;  // not reached: pass 1 checked the name
  };
  const auto to16 = [](int v) { return static_cast<std::uint16_t>(v); };
  const auto binary = [](unsigned op) {
    switch (op) {
      case kAdd: case kAddK: case kAddI: return Kind::add;
      case kSub: case kSubK: return Kind::sub;
      case kMul: case kMulK: return Kind::mul;
      case kMod: case kModK: return Kind::mod;
      case kPow: case kPowK: return Kind::pow;
      case kDiv: case kDivK: return Kind::div;
      default: return Kind::floor_div;
    }
  };
  for (int pc = 0; pc < count; ++pc) {
    if (!reached[static_cast<std::size_t>(pc)]) continue;
    const std::uint32_t i = chunk.code[static_cast<std::size_t>(pc)];
    const unsigned a = a_of(i);
    Op op;
    op.a = to16(static_cast<int>(a));
    switch (op_of(i)) {
      case kMove: op.kind = Kind::copy; op.b = to16(static_cast<int>(b_of(i))); break;
      case kLoadI: case kLoadF: op.kind = Kind::copy; op.b = to16(constant_slot(sbx_of(i))); break;
      case kLoadK: op.kind = Kind::copy; op.b = to16(constant_slot(constant_value(bx_of(i)))); break;
      case kGetUpval: op.kind = Kind::copy; op.b = to16(upvalue_value_slot(b_of(i))); break;
      case kGetField: op.kind = Kind::copy; op.b = to16(field_value_slot(chunk.constants[c_of(i)].text)); break;
      case kAddI:
        op.kind = Kind::add;
        op.b = to16(static_cast<int>(b_of(i)));
        op.c = to16(constant_slot(sc_of(i)));
        break;
      case kAddK: case kSubK: case kMulK: case kModK: case kPowK: case kDivK: case kIDivK:
        op.kind = binary(op_of(i));
        op.b = to16(static_cast<int>(b_of(i)));
        op.c = to16(constant_slot(constant_value(c_of(i))));
        break;
      case kAdd: case kSub: case kMul: case kMod: case kPow: case kDiv: case kIDiv:
        op.kind = binary(op_of(i));
        op.b = to16(static_cast<int>(b_of(i)));
        op.c = to16(static_cast<int>(c_of(i)));
        break;
      case kUnm: op.kind = Kind::negate; op.b = to16(static_cast<int>(b_of(i))); break;
      case kJmp: op.kind = Kind::jump; op.target = to16(op_index[static_cast<std::size_t>(pc + 1 + sj_of(i))]); break;
      case kEq: case kLt: case kLe: case kEqK: case kEqI: case kLtI: case kLeI: case kGtI: case kGeI: {
        // Lua: if ((R[A] op operand) != k) skip the JMP that follows, else take it. Here:
        // if ((b op c) != expect) goto the instruction after the JMP.
        const unsigned code = op_of(i);
        const int reg_a = static_cast<int>(a);
        int left = reg_a;
        int right = 0;
        if (code == kEq || code == kLt || code == kLe) right = static_cast<int>(b_of(i));
        else if (code == kEqK) right = constant_slot(constant_value(b_of(i)));
        else right = constant_slot(sb_of(i));
        if (code == kGtI || code == kGeI) std::swap(left, right);  // R[A] > im is im < R[A]
        op.kind = (code == kEq || code == kEqK || code == kEqI) ? Kind::branch_eq
                  : (code == kLt || code == kLtI || code == kGtI) ? Kind::branch_lt
                                                                  : Kind::branch_le;
        op.b = to16(left);
        op.c = to16(right);
        op.expect = k_of(i);
        op.target = to16(op_index[static_cast<std::size_t>(pc + 2)]);
        break;
      }
      case kReturn: op.kind = Kind::give_back; op.c = to16(static_cast<int>(b_of(i)) - 1); break;
      case kReturn0: op.kind = Kind::give_back; op.c = 0; break;
      case kReturn1: op.kind = Kind::give_back; op.c = 1; break;
      default: return std::nullopt;  // not reached: pass 1 refused it
    }
    program.ops_.push_back(op);
  }
  if (program.values_.size() > 0xffff) return std::nullopt;
  if (!program.read_upvalues(L, function)) return std::nullopt;
  return program;
}

bool ForceProgram::read_upvalues(lua_State* L, int function_index) noexcept {
  const int function = lua_absindex(L, function_index);
  for (const Upvalue& u : upvalues_) {
    if (lua_getupvalue(L, function, u.index) == nullptr) return false;
    const bool ok = lua_type(L, -1) == LUA_TNUMBER && (lua_isinteger(L, -1) != 0) == u.integer;
    const double value = ok ? lua_tonumber(L, -1) : 0.0;
    lua_pop(L, 1);
    if (!ok || (u.integer && std::fabs(value) > kExactIntegerLimit)) return false;
    values_[static_cast<std::size_t>(u.slot)] = value;
  }
  return true;
}

int ForceProgram::run(double* results) noexcept {
  double* v = values_.data();
  const Op* ops = ops_.data();
  for (std::size_t pc = 0;;) {
    const Op& op = ops[pc++];
    switch (op.kind) {
      case Kind::copy: v[op.a] = v[op.b]; break;
      case Kind::negate: v[op.a] = -v[op.b]; break;
      case Kind::add: v[op.a] = v[op.b] + v[op.c]; break;
      case Kind::sub: v[op.a] = v[op.b] - v[op.c]; break;
      case Kind::mul: v[op.a] = v[op.b] * v[op.c]; break;
      case Kind::div: v[op.a] = v[op.b] / v[op.c]; break;
      case Kind::mod: {
        // luai_nummod: fmod, then the result takes the divisor's sign.
        const double x = v[op.b];
        const double y = v[op.c];
        double m = std::fmod(x, y);
        if ((m > 0) ? y < 0 : (m < 0 && y > 0)) m += y;
        v[op.a] = m;
        break;
      }
      case Kind::pow: {
        // luai_numpow: a square is a product.
        const double x = v[op.b];
        const double y = v[op.c];
        v[op.a] = y == 2 ? x * x : std::pow(x, y);
        break;
      }
      case Kind::floor_div: v[op.a] = std::floor(v[op.b] / v[op.c]); break;
      case Kind::branch_lt:
        if ((v[op.b] < v[op.c]) != op.expect) pc = op.target;
        break;
      case Kind::branch_le:
        if ((v[op.b] <= v[op.c]) != op.expect) pc = op.target;
        break;
      case Kind::branch_eq:
        if ((v[op.b] == v[op.c]) != op.expect) pc = op.target;
        break;
      case Kind::jump: pc = op.target; break;
      case Kind::give_back:
        if (op.c >= 1) results[0] = v[op.a];
        if (op.c >= 2) results[1] = v[op.a + 1];
        return op.c;
    }
  }
}

}  // namespace hapscene::detail
