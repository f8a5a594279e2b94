#pragma once
// Unwrapping the Hapkit's MR sensor. Its raw reading repeats every half turn of the motor
// shaft; a jump larger than the threshold is a "flip" into the next period, in the
// direction opposite to the jump. Unwrapped = raw + flips * span.
//
// A real sensor's output does not wrap in an instant: a sample can land on the way from
// one end of the range to the other (960, 500, 60), and then no jump between consecutive
// samples is above the threshold. So each sample is compared with the previous one and,
// when that is no flip, with up to two earlier samples since the last flip (the
// reference sketch compares with the sample two back for the same reason). A sequence
// whose consecutive jumps are all below the threshold and whose span over three samples
// is too unwraps exactly as comparing neighbours does; motion is followed while it moves
// less than threshold / 3 counts per sample (233 at 700: 3 m/s of handle at 1 kHz, 15 m/s
// at the board's 5 kHz).
// The intermediate sample itself reads where the sensor put it: one sample off.
//
// Portable on purpose (no library, no allocation, integers only) so the board's firmware
// and the host share it. Arithmetic is checked: a garbage reading (any int32) never
// overflows; a jump that does not fit 32 bits is no flip, the flip count saturates, and
// an unwrapped count beyond int32 saturates; each is counted in `overflows`.
#include <stdint.h>

namespace hapscene {

struct FlipCounter {
  // Samples compared: the previous one, then up to two earlier ones since the last flip.
  static constexpr uint8_t kWindow = 3;

  int32_t threshold_counts = 700;
  int32_t span_counts = 922;
  int32_t flips = 0;
  int32_t shift_counts = 0;           // flips * span_counts
  bool started = false;
  uint8_t recent_count = 0;           // valid entries of recent_raw
  int32_t recent_raw[kWindow] = {};   // recent_raw[0] the previous sample, then older
  uint32_t overflows = 0;             // arithmetic that would have overflowed

  // True when `raw_counts` lies within the threshold of every sample of a full window:
  // no flip, the common case, in straight-line code (the loop below decides the rest).
  // (Written out for the window of three: a loop here was not unrolled and cost the
  // host's tick about 40 instructions.)
  bool within_window(int32_t raw_counts) const {
    static_assert(kWindow == 3, "within_window compares with exactly three samples");
    if (recent_count != kWindow) return false;
#if INTPTR_MAX >= INT64_MAX
    // A 64-bit host: the differences of 32-bit counts are exact in 64 bits, nothing to
    // check for overflow. |jump| <= threshold as one unsigned comparison each.
    const int64_t threshold = threshold_counts;
    const uint64_t width = 2u * static_cast<uint64_t>(threshold);
    // (0 or 1 as unsigned: the three combine with & and no branch.)
    const auto near = [&](int32_t earlier) -> unsigned {
      return static_cast<uint64_t>(int64_t{raw_counts} - earlier + threshold) <= width;
    };
    return (near(recent_raw[0]) & near(recent_raw[1]) & near(recent_raw[2])) != 0u;
#else
    int32_t jump0, jump1, jump2;
    const bool overflowed = __builtin_sub_overflow(raw_counts, recent_raw[0], &jump0) |
                            __builtin_sub_overflow(raw_counts, recent_raw[1], &jump1) |
                            __builtin_sub_overflow(raw_counts, recent_raw[2], &jump2);
    // |jump| <= threshold as one unsigned comparison each.
    const uint32_t threshold = static_cast<uint32_t>(threshold_counts);
    const uint32_t width = 2u * threshold;
    return !overflowed & (static_cast<uint32_t>(jump0) + threshold <= width) &
           (static_cast<uint32_t>(jump1) + threshold <= width) &
           (static_cast<uint32_t>(jump2) + threshold <= width);
#endif
  }

  // Feeds one raw sample; returns the unwrapped count. The common case (within the
  // threshold of a full window: no flip) is inline, so a caller's tick makes no call for
  // it; the rest is out of line.
  int32_t update(int32_t raw_counts) {
    if (__builtin_expect(within_window(raw_counts), 1)) {
      remember(raw_counts);
      return unwrapped(raw_counts);
    }
    return update_with_flips(raw_counts);
  }

 private:
  // The window moves on by one sample.
  void remember(int32_t raw_counts) {
    recent_raw[2] = recent_raw[1];
    recent_raw[1] = recent_raw[0];
    recent_raw[0] = raw_counts;
  }

  // raw + shift, saturated (and counted) where it does not fit.
  int32_t unwrapped(int32_t raw_counts) {
    int32_t result;
    if (__builtin_add_overflow(raw_counts, shift_counts, &result)) {
      ++overflows;
      return shift_counts < 0 ? INT32_MIN : INT32_MAX;
    }
    return result;
  }

  // A sample that may be a flip, or one of the first samples.
  __attribute__((noinline)) int32_t update_with_flips(int32_t raw_counts) {
    if (started) {
      int8_t direction = 0;
      for (uint8_t i = 0; i < recent_count && direction == 0; ++i) {
        int32_t jump;
        if (__builtin_sub_overflow(raw_counts, recent_raw[i], &jump)) {
          ++overflows;
          break;
        }
        if (jump > threshold_counts) {
          direction = -1;  // wrapped downwards past the bottom
        } else if (jump < -threshold_counts) {
          direction = 1;   // wrapped upwards past the top
        }
      }
      if (direction != 0) {
        // The shift is recomputed only here (a multiplication is costly on the AVR).
        int32_t next_flips, next_shift;
        if (__builtin_add_overflow(flips, static_cast<int32_t>(direction), &next_flips) ||
            __builtin_mul_overflow(next_flips, span_counts, &next_shift)) {
          ++overflows;  // saturated: the count stays
        } else {
          flips = next_flips;
          shift_counts = next_shift;
        }
        recent_count = 0;  // a wrap counts once: compare only with samples after it
      }
    }
    started = true;
    remember(raw_counts);
    if (recent_count < kWindow) ++recent_count;
    return unwrapped(raw_counts);
  }
};

}  // namespace hapscene
