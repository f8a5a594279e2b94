#pragma once
// The bounds a number read from a file may take (engine/base/object_reader.hpp reads them;
// engine/base/physical_ranges.hpp lists the physical ones).

namespace hapscene {

// What values a number may take.
enum class Bound { any, non_negative, positive };

// A finite range [min, max] (SI) of a physical key, or (min, max] with min_excluded.
// Out-of-range values are refused naming the key: "must be in [0, 10000000] N/m, got
// 1e+308 N/m" (below a lower bound of 0, the Bound messages: "must be >= 0, got -5 N/m").
struct Range {
  double min{};
  double max{};
  bool min_excluded{};
};

}  // namespace hapscene
