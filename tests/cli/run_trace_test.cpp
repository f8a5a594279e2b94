// The `run --plot` trace: bounded memory whatever the run's length, the whole run
// covered, every force peak kept, short runs recorded tick by tick.
#include <doctest/doctest.h>

#include <cmath>

#include "engine/cli/run_trace.hpp"
#include "engine/scene/tick_state.hpp"

using namespace hapscene;

namespace {

// Feeds `ticks` ticks at 1 kHz with a force of sin(t) plus one spike at `spike_tick`.
void feed(RunTrace* trace, std::uint64_t ticks, std::uint64_t spike_tick) {
  TickState state;
  for (std::uint64_t i = 0; i < ticks; ++i) {
    state.t_s = static_cast<double>(i) * 1e-3;
    state.x_m = 1e-3 * std::sin(state.t_s);
    state.output_N = i == spike_tick ? 9.0 : std::sin(state.t_s);
    trace->on_tick(state);
  }
  trace->on_finish(state);
}

}  // namespace

TEST_CASE("run trace: a day-long run reserves a fixed amount, spans the run and keeps the peak") {
  const std::uint64_t day_ticks = 86'400'000;  // 24 h at 1 kHz
  RunTrace day(nullptr, day_ticks);
  CHECK(day.records().capacity() <= kMaxRunTraceRecords);
  CHECK(day.ticks_per_bucket() == 8640);

  // Two million ticks planned and run: the records stay within the cap and cover it all.
  const std::uint64_t ticks = 2'000'000;
  RunTrace trace(nullptr, ticks);
  feed(&trace, ticks, 1'234'567);
  const std::vector<TickRecord>& records = trace.records();
  CHECK(records.size() <= kMaxRunTraceRecords);
  CHECK(records.size() > kMaxRunTraceRecords / 2);
  CHECK(trace.dropped() == 0);
  CHECK(records.front().t_s < 0.2);
  CHECK(records.back().t_s > 1999.8);
  double peak_N = 0.0;
  for (std::size_t i = 1; i < records.size(); ++i) {
    CHECK(records[i].t_s > records[i - 1].t_s);  // time order, every record a real tick
    peak_N = std::max(peak_N, records[i].output_N);
  }
  CHECK(peak_N == 9.0);
}

TEST_CASE("run trace: a short run keeps every tick, as before") {
  RunTrace trace(nullptr, 2000);
  feed(&trace, 2000, 5);
  CHECK(trace.ticks_per_bucket() == 1);
  REQUIRE(trace.records().size() == 2000);
  CHECK(trace.records()[5].output_N == 9.0);
  CHECK(trace.records()[1999].t_s == doctest::Approx(1.999));
}
