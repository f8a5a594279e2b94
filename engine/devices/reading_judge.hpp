#pragma once
// Whether a board's reading can be a position: the one judgement every link makes before
// a torque may follow from a reading (BoardLink for the hapscene firmware on serial, hil
// and the two-board pair; HaplyLink for the Haply stock firmware). A reading is plausible
// when it is
//   finite,
//   within the sensor's range (the profile's), and
//   no farther from the last trusted reading than the device's top speed allows in the
//   time between them (plus the arrival jitter a serial link adds).
// The last trusted reading is the link's to say: the previous accepted one, or after a
// board's setup the value the board was told to read there (a Haply board presets its
// encoders). With none (the very first reading of a board that counts from anywhere)
// only finiteness and range are judged. Pure, allocation-free and noexcept: for the tick.
#include <cmath>
#include <cstdint>
#include <limits>

namespace hapscene {

// The sensor's range and speed bound, in the reading's own units (counts, degrees).
struct ReadingBounds {
  double min{-std::numeric_limits<double>::infinity()};
  double max{std::numeric_limits<double>::infinity()};
  double max_speed_per_s{std::numeric_limits<double>::infinity()};   // the fastest the reading can change
  std::int64_t slack_ns{};            // added to the time between two readings
};

// A reading already trusted, and when it was true.
struct TrustedReading {
  double value{};
  std::int64_t t_ns{};
};

enum class ReadingFault : std::uint8_t { none, not_finite, out_of_range, too_fast };

inline const char* reading_fault_name(ReadingFault fault) noexcept {
  switch (fault) {
    case ReadingFault::none: return "plausible";
    case ReadingFault::not_finite: return "not a finite number";
    case ReadingFault::out_of_range: return "outside the sensor's range";
    case ReadingFault::too_fast: return "farther than the device can move in the time since";
  }
  return "?";
}

// The verdict on `value` read at `now_ns`; `last` is null when nothing is trusted yet.
inline ReadingFault judge_reading(const ReadingBounds& bounds, double value, const TrustedReading* last,
                                  std::int64_t now_ns) noexcept {
  if (!std::isfinite(value)) return ReadingFault::not_finite;
  if (!(value >= bounds.min && value <= bounds.max)) return ReadingFault::out_of_range;
  if (last != nullptr) {
    const double elapsed_s =
        static_cast<double>((now_ns > last->t_ns ? now_ns - last->t_ns : 0) + bounds.slack_ns) * 1e-9;
    if (!(std::fabs(value - last->value) <= bounds.max_speed_per_s * elapsed_s)) return ReadingFault::too_fast;
  }
  return ReadingFault::none;
}

}  // namespace hapscene
