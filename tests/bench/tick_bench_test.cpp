// The bench's comparison: every implementation is timed in the same rounds, on the same
// slice of readings, in a rotating order, and its figures are medians over rounds. (The
// timings themselves are not checked here: tests do not time anything.)
#include <doctest/doctest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "engine/bench/tick_bench.hpp"
#include "tests/cli/cli_support.hpp"

namespace hapscene {
namespace {

struct Call {
  int loop;
  std::size_t begin, end;
};

// A loop that records its calls and reports a fixed cost per tick.
class RecordingLoop final : public TickLoop {
 public:
  RecordingLoop(int id, double ns, std::vector<Call>* calls) : id_(id), ns_(ns), calls_(calls) {}
  double time_slice(TickTimer&, const std::vector<std::int32_t>& counts, std::size_t begin,
                    std::size_t end) override {
    if (begin == 0 && end == counts.size()) ++whole_passes;  // warm-up
    else calls_->push_back({id_, begin, end});
    return ns_;
  }
  void time_tail(TickTimer&, const std::vector<std::int32_t>& counts, int passes, TickCost* cost) override {
    ++tails;
    cost->ticks = counts.size() * static_cast<std::size_t>(passes);
  }
  double instructions_per_tick(InstructionCounter&, const std::vector<std::int32_t>&) override { return -1.0; }
  int tails = 0;
  long whole_passes = 0;

 private:
  int id_;
  double ns_;
  std::vector<Call>* calls_;
};

TEST_CASE("bench: implementations are compared slice by slice in the same rounds, in rotating order") {
  std::vector<Call> calls;
  RecordingLoop a(0, 4.0, &calls), b(1, 6.0, &calls), c(2, 10.0, &calls), d(3, 3.0, &calls), e(4, 9.0, &calls);
  const std::vector<std::int32_t> long_counts(2 * kSliceTicks + 100), short_counts(kSliceTicks + 50);
  const std::vector<TickLoopGroup> groups = {{&long_counts, {&a, &b, &c}}, {&short_counts, {&d, &e}}};
  TickTimer timer;
  const int passes = 3;
  const auto costs = compare_tick_loops(groups, passes, &timer);

  // Warm-up first: whole passes of every loop. Then the timed rounds, single slices.
  for (const RecordingLoop* loop : {&a, &b, &c, &d, &e}) CHECK(loop->whole_passes >= 1);
  const std::vector<Call>& rounds = calls;
  // passes x the most slices of any group (2) rounds; each round times all five loops.
  REQUIRE(rounds.size() == 5u * passes * 2);
  for (std::size_t r = 0; r < rounds.size() / 5; ++r) {
    std::vector<int> seen;
    for (std::size_t i = 0; i < 5; ++i) seen.push_back(rounds[5 * r + i].loop);
    std::sort(seen.begin(), seen.end());
    CHECK(seen == std::vector<int>{0, 1, 2, 3, 4});
    // Within a group, one slice for all of its loops.
    for (std::size_t i = 1; i < 5; ++i) {
      const Call& call = rounds[5 * r + i];
      for (std::size_t j = 0; j < i; ++j) {
        const Call& other = rounds[5 * r + j];
        if ((call.loop < 3) == (other.loop < 3)) CHECK(call.begin == other.begin);
      }
      CHECK(call.end - call.begin == kSliceTicks);
    }
  }
  // The order rotates: the first loop timed in a group is not always the same.
  CHECK(rounds[0].loop != rounds[5].loop);

  REQUIRE(costs.size() == 2);
  REQUIRE(costs[0].size() == 3);
  REQUIRE(costs[1].size() == 2);
  CHECK(costs[0][0].median_ns == 4.0);
  CHECK(costs[0][0].ratio == 1.0);
  CHECK(costs[0][1].ratio == 1.5);
  CHECK(costs[0][2].ratio == 2.5);
  CHECK(costs[1][1].ratio == 3.0);
  CHECK(costs[1][1].ticks == short_counts.size() * passes);
  for (const RecordingLoop* loop : {&a, &b, &c, &d, &e}) CHECK(loop->tails == 1);
}

TEST_CASE("bench: the command prints the three implementations of a lab environment and its goals") {
  const test::CliOutcome outcome = test::run_cli("bench --seconds 0.5 --passes 2 environments/spring.json");
  CHECK(outcome.exit_code == 0);
  // The bench's own scenes (the parts table's walls that cannot act, on purpose) warn
  // nobody: only a user's file does.
  CHECK(outcome.err.find("warning") == std::string::npos);
  CHECK(outcome.out.find("build: ") == 0);  // timings name their build first
  CHECK(outcome.out.find("spring     hand-folded floor") != std::string::npos);
  CHECK(outcome.out.find("spring     sketch, inlined") != std::string::npos);
  CHECK(outcome.out.find("spring     sketch, call") != std::string::npos);
  CHECK(outcome.out.find("spring     built-in (JSON)") != std::string::npos);
  CHECK(outcome.out.find("spring     Lua script") != std::string::npos);
  // The spring's force is translated: the row beside it runs the same script in the VM alone.
  CHECK(outcome.out.find("spring     Lua script") < outcome.out.find("spring     Lua, VM only"));
  CHECK(outcome.out.find("spring     Lua, VM only") != std::string::npos);
  CHECK(outcome.out.find("spring: built-in ") != std::string::npos);
  CHECK(outcome.out.find("the lab sketch called out of line (goal <= 1.0x)") != std::string::npos);
  CHECK(outcome.out.find("the hand-folded floor (goal") == std::string::npos);  // printed, not judged
  CHECK(outcome.out.find("texture: 50000 fields ") != std::string::npos);
  CHECK(outcome.out.find("spring: Lua median ") != std::string::npos);
  CHECK(outcome.out.find("Lua rows: p99.9 <= 5x the median") != std::string::npos);
  CHECK(outcome.out.find("1.000 Lua calls per tick") != std::string::npos);

  const test::CliOutcome bad = test::run_cli("bench --passes 0");
  CHECK(bad.exit_code == 2);
  CHECK(bad.err.find("--passes: must be in [1, 1000]") != std::string::npos);
}

}  // namespace
}  // namespace hapscene
