#pragma once
// The one clock the loop and the device links read: CLOCK_MONOTONIC in nanoseconds.
#include <time.h>

#include <cstdint>

namespace hapscene {

inline std::int64_t monotonic_now_ns() noexcept {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  return static_cast<std::int64_t>(now.tv_sec) * 1'000'000'000 + now.tv_nsec;
}

}  // namespace hapscene
