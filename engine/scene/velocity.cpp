#include "engine/scene/velocity.hpp"

#include <cmath>
#include <numbers>

namespace hapscene {

double lowpass_alpha_for(double cutoff_Hz, double period_s) noexcept {
  return 1.0 - std::exp(-2.0 * std::numbers::pi * cutoff_Hz * period_s);
}

}  // namespace hapscene
