#pragma once
// Unwrapping the Hapkit's MR sensor. Its raw reading repeats every half turn of the motor
// shaft; a jump between consecutive samples larger than the threshold is a "flip" into
// the next period, in the direction opposite to the jump. Unwrapped = raw + flips * span.
//
// Portable on purpose (no library, no allocation, integers only) so the board's firmware
// and the host share it.
#include <stdint.h>

namespace hapscene {

struct FlipCounter {
  int32_t threshold_counts = 700;
  int32_t span_counts = 922;
  int32_t previous_raw = 0;
  int32_t flips = 0;
  bool started = false;

  // Feeds one raw sample; returns the unwrapped count. Garbage readings (any int32) give
  // garbage positions but never overflow: the jump and the result wrap as unsigned
  // arithmetic does, and the flip count saturates.
  int32_t update(int32_t raw_counts) {
    if (started) {
      const int32_t jump = static_cast<int32_t>(static_cast<uint32_t>(raw_counts) -
                                                static_cast<uint32_t>(previous_raw));
      if (jump > threshold_counts) {
        if (flips > -2147483647) --flips;  // wrapped downwards past the bottom
      } else if (jump < -threshold_counts) {
        if (flips < 2147483647) ++flips;   // wrapped upwards past the top
      }
    }
    started = true;
    previous_raw = raw_counts;
    return static_cast<int32_t>(static_cast<uint32_t>(raw_counts) +
                                static_cast<uint32_t>(flips) * static_cast<uint32_t>(span_counts));
  }
};

}  // namespace hapscene
