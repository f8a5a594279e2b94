// Fuzz target: the unit parser ("10 mm", "2 N*s/m", "1e-3 kHz") as every quantity, and the
// "did you mean" distance it uses on unknown units.
#include <cmath>

#include "engine/base/units.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace hapscene;
  const std::string_view text = fuzz::as_text(data, size);
  const QuantityParse any = parse_quantity(text);
  fuzz::fuzz_require(!any.ok || std::isfinite(any.value_si), "a parsed quantity is not finite");
  fuzz::fuzz_require(any.ok || !any.error.empty(), "a refused quantity has no message");
  for (int q = 0; q <= static_cast<int>(Quantity::force_rate_N_per_s); ++q) {
    const QuantityParse as = parse_quantity_as(text, static_cast<Quantity>(q));
    fuzz::fuzz_require(!as.ok || std::isfinite(as.value_si), "a parsed quantity is not finite");
    fuzz::fuzz_require(as.ok || !as.error.empty(), "a refused quantity has no message");
  }
  // Split in two: the distance is symmetric, and (for names short enough to be measured
  // at all) zero only for equal names.
  const std::string_view a = text.substr(0, size / 2);
  const std::string_view b = text.substr(size / 2);
  const std::size_t ab = edit_distance(a, b);
  fuzz::fuzz_require(ab == edit_distance(b, a), "edit distance is not symmetric");
  if (a.size() <= kMaxSuggestedNameBytes && b.size() <= kMaxSuggestedNameBytes) {
    fuzz::fuzz_require((ab == 0) == (a == b), "edit distance 0 for different names");
  }
  return 0;
}
