#pragma once
// Seeded, portable noise for simulated sensors: the same seed gives the same sequence on
// every machine (the standard library's distributions do not promise that).
#include <cmath>
#include <cstdint>
#include <numbers>

namespace hapscene {

class GaussianNoise {
 public:
  explicit GaussianNoise(std::uint64_t seed) : state_(seed) {}

  // A standard normal sample (Box-Muller on splitmix64).
  double next() noexcept {
    const double u1 = (static_cast<double>(next_u64() >> 11) + 0.5) * 0x1.0p-53;
    const double u2 = static_cast<double>(next_u64() >> 11) * 0x1.0p-53;
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
  }

 private:
  std::uint64_t next_u64() noexcept {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }

  std::uint64_t state_;
};

}  // namespace hapscene
