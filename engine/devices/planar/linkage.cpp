#include "engine/devices/planar/linkage.hpp"

#include <cmath>
#include <limits>

namespace hapscene {
// For a 2x2 matrix the singular values follow from the Frobenius norm and the determinant:
// s1^2 + s2^2 = |J|_F^2 and s1 s2 = |det J|, so s1 = (sqrt(F^2 + 2|det|) + sqrt(F^2 - 2|det|)) / 2
// and the condition number s1 / s2 = s1^2 / |det|.
double condition_number(const Jacobian2& j) noexcept {
  const double a = j.m[0][0], b = j.m[0][1], c = j.m[1][0], d = j.m[1][1];
  const double frobenius_sq = a * a + b * b + c * c + d * d;
  const double det = std::fabs(a * d - b * c);
  if (!std::isfinite(frobenius_sq) || !std::isfinite(det) || det == 0.0) {
    return std::numeric_limits<double>::infinity();
  }
  const double sum = std::sqrt(frobenius_sq + 2.0 * det);
  const double difference = std::sqrt(std::fmax(frobenius_sq - 2.0 * det, 0.0));
  const double s1 = 0.5 * (sum + difference);
  return std::fmax(s1 * s1 / det, 1.0);
}

}  // namespace hapscene
