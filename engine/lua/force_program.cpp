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
  kMove = 0, kLoadI = 1, kLoadF = 2, kLoadK = 3, kLoadNil = 8,
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

// Whether the translation may hold the integer `n` as the double it converts to. Lua
// converts an integer to a float for arithmetic with a float (the C conversion, as here),
// but compares integers with integers and with floats mathematically exactly (lvm.c:
// LTintfloat, luaV_equalobj): 2^53 + 1 > 2^53.0 is true, while its nearest double equals
// 2^53. Comparing doubles gives Lua's answer only when every integer is exactly its
// double, so only such integers are taken: n converts to a double and back to n. The
// double is checked to be in [-2^63, 2^63) before it is converted back (outside, the
// conversion is undefined; LUA_MAXINTEGER rounds up to 2^63 and is refused there).
// LUA_MININTEGER (-2^63, exact) is refused too: Lua's -n wraps it to itself, and the
// translation's -n (integer negation: 0 - n) would give +2^63.
bool exact_integer(lua_Integer n) {
  const auto d = static_cast<double>(n);
  constexpr double kTwoTo63 = 9223372036854775808.0;
  if (!(d >= -kTwoTo63 && d < kTwoTo63)) return false;
  return static_cast<lua_Integer>(d) == n && n != LUA_MININTEGER;
}

}  // namespace

std::optional<ForceProgram> ForceProgram::translate(const FunctionChunk& chunk,
                                                    const std::array<const char*, kFieldCount>& fields, lua_State* L,
                                                    int function_index) {
  const int count = static_cast<int>(chunk.code.size());
  const int registers = chunk.stack_size;
  if (chunk.vararg || chunk.parameters < 1 || count == 0 || count > 1024 || registers < 1) return std::nullopt;
  const auto u = [](auto v) { return static_cast<std::size_t>(v); };

  // Slots: the fields of s, the registers, then constants and upvalues as they are met.
  ForceProgram program;
  program.values_.assign(u(kFieldCount + registers), 0.0);
  const auto register_slot = [&](unsigned r) { return kFieldCount + static_cast<int>(r); };
  std::vector<bool> constant_slots(program.values_.size(), false);
  const auto constant_slot = [&](double value) {
    for (std::size_t slot = 0; slot < program.values_.size(); ++slot) {
      // The same bits (0.0 and -0.0 stay apart).
      if (constant_slots[slot] && std::memcmp(&program.values_[slot], &value, sizeof value) == 0) {
        return static_cast<int>(slot);
      }
    }
    program.values_.push_back(value);
    constant_slots.push_back(true);
    return static_cast<int>(program.values_.size()) - 1;
  };

  // Upvalues that hold numbers now: a slot each, filled by read_upvalues.
  std::vector<int> upvalue_slot(u(chunk.upvalue_count), -1);
  std::vector<Holds> upvalue_holds(u(chunk.upvalue_count), Holds::none);
  const int function = lua_absindex(L, function_index);
  for (int up = 0; up < chunk.upvalue_count; ++up) {
    if (lua_getupvalue(L, function, up + 1) == nullptr) return std::nullopt;
    if (lua_type(L, -1) == LUA_TNUMBER) {
      const bool integer = lua_isinteger(L, -1) != 0;
      if (!integer || exact_integer(lua_tointeger(L, -1))) {
        upvalue_holds[u(up)] = integer ? Holds::integer : Holds::number;
      }
    }
    lua_pop(L, 1);
  }
  const auto upvalue_value_slot = [&](unsigned up) {
    if (upvalue_slot[up] < 0) {
      program.values_.push_back(0.0);
      constant_slots.push_back(false);
      upvalue_slot[up] = static_cast<int>(program.values_.size()) - 1;
      program.upvalues_.push_back({static_cast<int>(up) + 1, upvalue_slot[up], upvalue_holds[up] == Holds::integer});
    }
    return upvalue_slot[up];
  };

  const auto constant_holds = [&](unsigned index) {
    if (index >= chunk.constants.size()) return Holds::none;
    const LuaConstant& k = chunk.constants[index];
    if (k.kind == LuaConstant::Kind::number) return Holds::number;
    if (k.kind == LuaConstant::Kind::integer && exact_integer(k.integer)) return Holds::integer;
    return Holds::none;
  };
  const auto constant_value = [&](unsigned index) {
    const LuaConstant& k = chunk.constants[index];
    return k.kind == LuaConstant::Kind::number ? k.number : static_cast<double>(k.integer);
  };
  const auto is_number = [](Holds h) { return h == Holds::integer || h == Holds::number; };

  // What each register holds at each reachable instruction, and which slot it equals
  // there when it was loaded from one that a run never changes (a field, an upvalue, a
  // constant): operands read that slot directly, and the load is left out unless some
  // read of the register does not know the slot (paths that loaded different slots meet).
  constexpr int kComputed = -1;  // written by an op that is always kept: read the register
  constexpr int kMixed = -2;     // paths meet with different slots: the loads must be kept
  struct State {
    std::vector<Holds> holds;
    std::vector<int> alias;
  };
  std::vector<State> states(u(count) + 1, State{std::vector<Holds>(u(registers), Holds::unreached),
                                                 std::vector<int>(u(registers), kComputed)});
  std::vector<bool> reached(u(count) + 1, false);
  reached[0] = true;
  for (int r = 0; r < registers; ++r) states[0].holds[u(r)] = r == 0 ? Holds::state : Holds::none;
  const auto flow = [&](int to, const State& state) {
    if (to < 0 || to > count) return false;
    State& into = states[u(to)];
    for (std::size_t r = 0; r < state.holds.size(); ++r) {
      into.alias[r] = (into.holds[r] == Holds::unreached || into.alias[r] == state.alias[r]) ? state.alias[r] : kMixed;
      into.holds[r] = merge(into.holds[r], state.holds[r]);
    }
    reached[u(to)] = true;
    return true;
  };
  // After an arithmetic instruction Lua skips the MMBIN that follows (it only runs when
  // an operand is not a number).
  const auto after_arithmetic = [&](int pc) {
    if (pc + 1 >= count) return pc + 1;
    const unsigned next = op_of(chunk.code[u(pc + 1)]);
    return (next == kMmBin || next == kMmBinI || next == kMmBinK) ? pc + 2 : pc + 1;
  };
  // Lua's integer arithmetic applies when both operands are integers, except for / and ^.
  const auto arithmetic_result = [](unsigned op, Holds left, Holds right) {
    const bool float_only = op == kDiv || op == kDivK || op == kPow || op == kPowK;
    if (left == Holds::integer && right == Holds::integer && !float_only) return Holds::none;
    return Holds::number;
  };

  // Each reachable instruction as an op (with `loads_into` >= 0 for a load that may be
  // left out), its operands resolved to slots.
  struct Planned {
    Op op;
    int loads_into = -1;  // the register a pure load writes
    bool dropped = false;  // nothing to run (a nil that is never read as a number)
  };
  std::vector<Planned> planned(u(count));
  std::vector<bool> read_unaliased(u(registers), false);  // some read does not know the slot
  const auto fail = std::nullopt;

  for (int pc = 0; pc < count; ++pc) {
    if (!reached[u(pc)]) continue;
    const std::uint32_t i = chunk.code[u(pc)];
    State state = states[u(pc)];
    const unsigned a = a_of(i);
    const unsigned opcode = op_of(i);
    if (a >= static_cast<unsigned>(registers) && opcode != kJmp) return fail;
    const auto holds = [&](unsigned r) { return r < static_cast<unsigned>(registers) ? state.holds[r] : Holds::none; };
    // The slot an operand register is read from (and whether it is a number).
    const auto operand = [&](unsigned r) {
      if (state.alias[r] >= 0) return state.alias[r];
      if (state.alias[r] == kMixed) read_unaliased[r] = true;
      return register_slot(r);
    };
    const auto define = [&](unsigned r, Holds h, int alias) {
      state.holds[r] = h;
      state.alias[r] = alias;
    };
    Op& op = planned[u(pc)].op;
    op.a = static_cast<std::uint16_t>(register_slot(a));
    const auto load = [&](int slot, Holds h) {
      op.kind = Kind::copy;
      op.b = static_cast<std::uint16_t>(slot);
      planned[u(pc)].loads_into = static_cast<int>(a);
      define(a, h, slot);
    };
    // An arithmetic op on constants and upvalues only: computed once per read of the
    // upvalues into a slot of its own, which the register then equals (like a load).
    const auto hoist_if_invariant = [&]() {
      const int first_invariant = kFieldCount + registers;
      if (op.b < first_invariant || (op.kind != Kind::negate && op.c < first_invariant)) return;
      Op invariant = op;
      program.values_.push_back(0.0);
      constant_slots.push_back(false);
      invariant.a = static_cast<std::uint16_t>(program.values_.size() - 1);
      program.invariant_ops_.push_back(invariant);
      load(invariant.a, state.holds[a]);
    };
    int next = pc + 1;  // where control goes on (-1: nowhere, a return)
    switch (opcode) {
      case kMove:
        if (!is_number(holds(b_of(i)))) return fail;
        if (state.alias[b_of(i)] >= 0) {
          load(state.alias[b_of(i)], holds(b_of(i)));
        } else {
          op.kind = Kind::copy;
          op.b = static_cast<std::uint16_t>(operand(b_of(i)));
          define(a, holds(b_of(i)), kComputed);
        }
        break;
      case kLoadNil:  // `local a` before an `if` assigns it: reading it as nil is refused
        if (a + b_of(i) >= static_cast<unsigned>(registers)) return fail;
        for (unsigned r = a; r <= a + b_of(i); ++r) define(r, Holds::none, kComputed);
        planned[u(pc)].dropped = true;
        break;
      case kLoadI: load(constant_slot(sbx_of(i)), Holds::integer); break;
      case kLoadF: load(constant_slot(sbx_of(i)), Holds::number); break;
      case kLoadK: {
        const Holds h = constant_holds(bx_of(i));
        if (!is_number(h)) return fail;
        load(constant_slot(constant_value(bx_of(i))), h);
        break;
      }
      case kGetUpval: {
        const unsigned up = b_of(i);
        if (up >= upvalue_holds.size() || !is_number(upvalue_holds[up])) return fail;
        load(upvalue_value_slot(up), upvalue_holds[up]);
        break;
      }
      case kGetField: {
        if (holds(b_of(i)) != Holds::state || c_of(i) >= chunk.constants.size()) return fail;
        const LuaConstant& key = chunk.constants[c_of(i)];
        if (key.kind != LuaConstant::Kind::string) return fail;
        int field = -1;
        for (int f = 0; f < kFieldCount; ++f) {
          if (fields[u(f)] != nullptr && key.text == fields[u(f)]) field = f;
        }
        if (field < 0) return fail;  // Lua raises "s has no field ...": the VM says so
        load(field, Holds::number);
        break;
      }
      case kAddI: case kAddK: case kSubK: case kMulK: case kModK: case kPowK: case kDivK: case kIDivK:
      case kAdd: case kSub: case kMul: case kMod: case kPow: case kDiv: case kIDiv: {
        const Holds left = holds(b_of(i));
        Holds right = Holds::none;
        int right_slot = 0;
        if (opcode == kAddI) {
          right = Holds::integer;
          right_slot = constant_slot(sc_of(i));
        } else if (opcode >= kAddK && opcode <= kIDivK) {
          right = constant_holds(c_of(i));
          if (is_number(right)) right_slot = constant_slot(constant_value(c_of(i)));
        } else {
          right = holds(c_of(i));
          if (is_number(right)) right_slot = operand(c_of(i));
        }
        if (!is_number(left) || !is_number(right)) return fail;
        const Holds result = arithmetic_result(opcode, left, right);
        if (result == Holds::none) return fail;
        switch (opcode) {
          case kAdd: case kAddK: case kAddI: op.kind = Kind::add; break;
          case kSub: case kSubK: op.kind = Kind::sub; break;
          case kMul: case kMulK: op.kind = Kind::mul; break;
          case kMod: case kModK: op.kind = Kind::mod; break;
          case kPow: case kPowK: op.kind = Kind::pow; break;
          case kDiv: case kDivK: op.kind = Kind::div; break;
          default: op.kind = Kind::floor_div; break;
        }
        op.b = static_cast<std::uint16_t>(operand(b_of(i)));
        op.c = static_cast<std::uint16_t>(right_slot);
        define(a, result, kComputed);
        hoist_if_invariant();
        next = after_arithmetic(pc);
        break;
      }
      case kUnm:
        // -integer stays an integer, exactly its double (exact_integer: -n of such an n is
        // one too). An integer is negated as 0 - n: integer zero has no sign, and -0.0
        // would have one.
        if (!is_number(holds(b_of(i)))) return fail;
        if (holds(b_of(i)) == Holds::integer) {
          op.kind = Kind::sub;
          op.b = static_cast<std::uint16_t>(constant_slot(0.0));
          op.c = static_cast<std::uint16_t>(operand(b_of(i)));
        } else {
          op.kind = Kind::negate;
          op.b = static_cast<std::uint16_t>(operand(b_of(i)));
        }
        define(a, holds(b_of(i)), kComputed);
        hoist_if_invariant();
        break;
      case kJmp:
        if (sj_of(i) < 0) return fail;
        op.kind = Kind::jump;
        next = pc + 1 + sj_of(i);
        if (!flow(next, state)) return fail;
        next = -1;
        break;
      case kEq: case kLt: case kLe: case kEqK: case kEqI: case kLtI: case kLeI: case kGtI: case kGeI: {
        // Lua: if ((R[A] op operand) != k) skip the JMP that follows, else take it. Here:
        // if ((b op c) != expect) go to the instruction after the JMP.
        if (!is_number(holds(a))) return fail;
        if (pc + 1 >= count || op_of(chunk.code[u(pc + 1)]) != kJmp) return fail;
        int left = operand(a);
        int right = 0;
        if (opcode == kEq || opcode == kLt || opcode == kLe) {
          if (!is_number(holds(b_of(i)))) return fail;
          right = operand(b_of(i));
        } else if (opcode == kEqK) {
          if (!is_number(constant_holds(b_of(i)))) return fail;
          right = constant_slot(constant_value(b_of(i)));
        } else {
          right = constant_slot(sb_of(i));
        }
        if (opcode == kGtI || opcode == kGeI) std::swap(left, right);  // R[A] > im is im < R[A]
        op.kind = (opcode == kEq || opcode == kEqK || opcode == kEqI) ? Kind::branch_eq
                  : (opcode == kLt || opcode == kLtI || opcode == kGtI) ? Kind::branch_lt
                                                                        : Kind::branch_le;
        op.b = static_cast<std::uint16_t>(left);
        op.c = static_cast<std::uint16_t>(right);
        op.expect = k_of(i);
        flow(pc + 2, state);  // the target is set once the ops are numbered
        break;
      }
      case kReturn: case kReturn0: case kReturn1: {
        const unsigned values = opcode == kReturn ? b_of(i) - 1 : opcode == kReturn1 ? 1u : 0u;
        if (opcode == kReturn && b_of(i) == 0) return fail;  // as many values as on the stack
        for (unsigned r = a; r < a + values; ++r) {
          if (!is_number(holds(r))) return fail;
        }
        op.kind = Kind::give_back;
        op.a = static_cast<std::uint16_t>(values);
        if (values >= 1) op.b = static_cast<std::uint16_t>(operand(a));
        if (values >= 2) op.c = static_cast<std::uint16_t>(operand(a + 1));
        next = -1;
        break;
      }
      default: return fail;
    }
    if (next >= 0 && !flow(next, state)) return fail;
  }
  if (reached[u(count)]) return fail;  // runs off the end

  // Number the ops that are kept (a load is kept when some read of its register does not
  // know the slot; MMBINs are never reached), then fill in the targets.
  const auto kept = [&](int pc) {
    return reached[u(pc)] && !planned[u(pc)].dropped &&
           (planned[u(pc)].loads_into < 0 || read_unaliased[u(planned[u(pc)].loads_into)]);
  };
  std::vector<int> op_index(u(count) + 1, 0);
  int numbered = 0;
  for (int pc = 0; pc <= count; ++pc) {
    op_index[u(pc)] = numbered;
    if (pc < count && kept(pc)) ++numbered;
  }
  for (int pc = 0; pc < count; ++pc) {
    if (!kept(pc)) continue;
    Op op = planned[u(pc)].op;
    const std::uint32_t i = chunk.code[u(pc)];
    if (op.kind == Kind::jump) op.a = static_cast<std::uint16_t>(op_index[u(pc + 1 + sj_of(i))]);
    if (op.kind == Kind::branch_lt || op.kind == Kind::branch_le || op.kind == Kind::branch_eq) {
      op.a = static_cast<std::uint16_t>(op_index[u(pc + 2)]);
    }
    program.ops_.push_back(op);
  }
  Op end_invariants;
  end_invariants.kind = Kind::give_back;
  program.invariant_ops_.push_back(end_invariants);
  if (program.values_.size() > 0xffff) return fail;
  if (!program.read_upvalues(L, function)) return fail;
  return program;
}

bool ForceProgram::read_upvalues(lua_State* L, int function_index) noexcept {
  const int function = lua_absindex(L, function_index);
  for (const Upvalue& u : upvalues_) {
    if (lua_getupvalue(L, function, u.index) == nullptr) return false;
    const bool ok = lua_type(L, -1) == LUA_TNUMBER && (lua_isinteger(L, -1) != 0) == u.integer &&
                    (!u.integer || exact_integer(lua_tointeger(L, -1)));
    const double value = ok ? lua_tonumber(L, -1) : 0.0;
    lua_pop(L, 1);
    if (!ok) return false;
    values_[static_cast<std::size_t>(u.slot)] = value;
  }
  double unused[kMaxResults];
  execute(invariant_ops_.data(), values_.data(), unused);
  return true;
}

int ForceProgram::run(double* results) noexcept { return execute(ops_.data(), values_.data(), results); }

int ForceProgram::execute(const Op* ops, double* v, double* results) noexcept {
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
        if ((v[op.b] < v[op.c]) != op.expect) pc = op.a;
        break;
      case Kind::branch_le:
        if ((v[op.b] <= v[op.c]) != op.expect) pc = op.a;
        break;
      case Kind::branch_eq:
        if ((v[op.b] == v[op.c]) != op.expect) pc = op.a;
        break;
      case Kind::jump: pc = op.a; break;
      case Kind::give_back:
        results[0] = v[op.b];
        results[1] = v[op.c];
        return op.a;
      default: __builtin_unreachable();  // every op is one of the kinds above
    }
  }
}

}  // namespace hapscene::detail
