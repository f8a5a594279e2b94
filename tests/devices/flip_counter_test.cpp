// The MR sensor's unwrapping on recorded-style sequences: sweeps through the wrap with
// one or two samples caught on the way across, noise at the wrap, both directions, fast
// motion; smooth motion unwraps exactly as the neighbour-only counter did; garbage never
// overflows.
#include <doctest/doctest.h>

#include <algorithm>
#include <climits>
#include <cstdint>
#include <random>
#include <vector>

#include "protocol/flip_counter.hpp"

using namespace hapscene;

namespace {

constexpr std::int32_t kMin = 50, kSpan = 922, kThreshold = 700;

// The counter before intermediate samples were handled: neighbours only.
struct NeighbourFlipCounter {
  std::int32_t previous_raw = 0, flips = 0;
  bool started = false;
  std::int32_t update(std::int32_t raw) {
    if (started) {
      const std::int32_t jump = raw - previous_raw;
      if (jump > kThreshold) --flips;
      if (jump < -kThreshold) ++flips;
    }
    started = true;
    previous_raw = raw;
    return raw + flips * kSpan;
  }
};

// One sensor sample: the raw reading, and where the handle really is (unwrapped), or
// none for a sample caught while the output swings across the wrap.
struct Sample {
  std::int32_t raw;
  std::int32_t truth;
  bool in_transit;
};

std::int32_t wrap(std::int32_t unwrapped) {
  std::int32_t within = (unwrapped - kMin) % kSpan;
  if (within < 0) within += kSpan;
  return kMin + within;
}

std::int32_t period_of(std::int32_t unwrapped) {
  const std::int32_t d = unwrapped - kMin;
  return d >= 0 ? d / kSpan : -((-d + kSpan - 1) / kSpan);
}

// A recording of the handle moving through `positions` (unwrapped counts, noise already
// in them); at every wrap, `transit` samples land on the way from one end to the other
// at the given fractions of the swing.
std::vector<Sample> record(const std::vector<std::int32_t>& positions, const std::vector<double>& transit) {
  std::vector<Sample> samples;
  for (std::size_t k = 0; k < positions.size(); ++k) {
    const std::int32_t raw = wrap(positions[k]);
    if (k > 0 && period_of(positions[k]) != period_of(positions[k - 1])) {
      const std::int32_t from = wrap(positions[k - 1]);
      for (const double f : transit) {
        samples.push_back({static_cast<std::int32_t>(from + f * (raw - from)), 0, true});
      }
    }
    samples.push_back({raw, positions[k], false});
  }
  return samples;
}

// A sweep from `from` to `to` in steps of `step` counts, with uniform noise of +-noise.
std::vector<std::int32_t> sweep(std::int32_t from, std::int32_t to, std::int32_t step, std::int32_t noise,
                                std::uint32_t seed) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<std::int32_t> jitter(-noise, noise);
  std::vector<std::int32_t> positions;
  const std::int32_t direction = to >= from ? 1 : -1;
  for (std::int32_t u = from; direction * (to - u) >= 0; u += direction * step) positions.push_back(u + jitter(random));
  return positions;
}

// Feeds `samples`; every sample not in transit must unwrap to where the handle is
// (relative to the first sample). Returns how many did not.
template <class Counter>
int misplaced(const std::vector<Sample>& samples, Counter counter) {
  const std::int32_t offset = samples.front().truth - samples.front().raw;
  int wrong = 0;
  for (const Sample& s : samples) {
    const std::int32_t unwrapped = counter.update(s.raw);
    if (!s.in_transit && unwrapped + offset != s.truth) ++wrong;
  }
  return wrong;
}

FlipCounter hapkit_counter() { return FlipCounter{.threshold_counts = kThreshold, .span_counts = kSpan}; }

}  // namespace

TEST_CASE("flip counter: a sample caught on the way across the wrap costs no period") {
  // 960 -> 500 -> 60: no neighbour jump reaches 700, the one across two samples does.
  FlipCounter counter = hapkit_counter();
  CHECK(counter.update(960) == 960);
  CHECK(counter.update(500) == 500);  // in transit: reads where the sensor put it
  CHECK(counter.update(60) == 60 + kSpan);
  CHECK(counter.update(80) == 80 + kSpan);
  // And back down, with two samples in transit.
  CHECK(counter.update(70) == 70 + kSpan);
  CHECK(counter.update(350) == 350 + kSpan);
  CHECK(counter.update(700) == 700 + kSpan);
  CHECK(counter.update(965) == 965);
  CHECK(counter.update(950) == 950);
  // The neighbour-only counter loses a period at the first wrap.
  NeighbourFlipCounter old;
  for (const std::int32_t raw : {960, 500, 60}) old.update(raw);
  CHECK(old.update(80) == 80);  // a whole period off
}

TEST_CASE("flip counter: sweeps through several wraps with samples in transit, both directions") {
  const std::vector<std::vector<double>> transits = {{0.5}, {0.2}, {0.8}, {0.25, 0.75}, {0.1, 0.5}, {0.6, 0.95}};
  for (const auto& transit : transits) {
    for (const std::int32_t step : {3, 40, 150, 220}) {
      CAPTURE(transit.size());
      CAPTURE(transit.front());
      CAPTURE(step);
      const auto up = record(sweep(200, 200 + 4 * kSpan, step, 0, 1), transit);
      const auto down = record(sweep(200 + 4 * kSpan, -2 * kSpan, step, 0, 2), transit);
      CHECK(misplaced(up, hapkit_counter()) == 0);
      CHECK(misplaced(down, hapkit_counter()) == 0);
      // Without the fix: a period lost at every wrap caught in transit.
      if (transit.front() > 0.25 && transit.front() < 0.75) CHECK(misplaced(up, NeighbourFlipCounter{}) > 0);
    }
  }
}

TEST_CASE("flip counter: noise at the wrap, with and without samples in transit") {
  // The handle rests on the wrap; the reading dithers across it by a few counts.
  for (const std::uint32_t seed : {1u, 2u, 3u, 4u}) {
    std::mt19937 random(seed);
    std::uniform_int_distribution<std::int32_t> jitter(-4, 4);
    std::uniform_int_distribution<int> transit_chance(0, 4);
    std::vector<Sample> samples;
    const std::int32_t wrap_point = kMin + 3 * kSpan;
    std::int32_t previous = wrap_point - 10;
    samples.push_back({wrap(previous), previous, false});
    for (int k = 0; k < 2000; ++k) {
      const std::int32_t position = wrap_point + jitter(random);
      if (period_of(position) != period_of(previous) && transit_chance(random) == 0) {
        // Now and then a sample lands halfway through the swing.
        samples.push_back({(wrap(previous) + wrap(position)) / 2, 0, true});
      }
      samples.push_back({wrap(position), position, false});
      previous = position;
    }
    CAPTURE(seed);
    CHECK(misplaced(samples, hapkit_counter()) == 0);
  }
  // Jumps close to the threshold on either side: 701 is a flip, 699 needs its neighbours.
  FlipCounter counter = hapkit_counter();
  counter.update(751);
  CHECK(counter.update(50) == 50 + kSpan);  // 701 down: flip
  FlipCounter near = hapkit_counter();
  near.update(749);
  CHECK(near.update(50) == 50);  // 699: motion, not a flip
}

TEST_CASE("flip counter: smooth motion unwraps exactly as comparing neighbours did") {
  // Random walks and sweeps below threshold / 3 per sample, across many wraps: the two
  // counters agree on every sample (so recorded and simulated runs are unchanged).
  for (const std::uint32_t seed : {11u, 12u, 13u, 14u, 15u}) {
    std::mt19937 random(seed);
    std::uniform_int_distribution<std::int32_t> velocity_change(-20, 20);
    std::int32_t position = 500, velocity = 0;
    FlipCounter counter = hapkit_counter();
    NeighbourFlipCounter old;
    int differences = 0;
    for (int k = 0; k < 20000; ++k) {
      velocity = std::clamp(velocity + velocity_change(random), -200, 200);
      position += velocity;
      const std::int32_t raw = wrap(position);
      differences += counter.update(raw) != old.update(raw);
    }
    CAPTURE(seed);
    CHECK(differences == 0);
  }
}

TEST_CASE("flip counter: garbage readings never overflow, the overflow is counted") {
  FlipCounter counter = hapkit_counter();
  for (const std::int32_t raw : {INT32_MIN, INT32_MAX, INT32_MIN, 0, INT32_MAX, -1, INT32_MIN}) counter.update(raw);
  CHECK(counter.overflows > 0);
  // Flips saturate where their shift would overflow.
  FlipCounter many{.threshold_counts = kThreshold, .span_counts = 1'500'000'000};
  for (const std::int32_t raw : {960, 60, 250, 450, 650, 850, 960}) many.update(raw);
  CHECK(many.flips == 1);
  CHECK(many.update(60) == 60 + 1'500'000'000);  // a second flip would need 3e9
  CHECK(many.flips == 1);
  CHECK(many.overflows > 0);
}
