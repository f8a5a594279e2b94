#include "engine/harness/option_ranges.hpp"

#include <cmath>

#include "engine/base/object_reader.hpp"

namespace hapscene {
namespace {

std::string unit_of(const ValueRange& range) {
  return std::string(range.unit.empty() ? si_unit(range.quantity) : range.unit);
}

}  // namespace

std::string describe_range(const ValueRange& range) {
  const std::string unit = unit_of(range);
  return std::string(range.min_exclusive ? "(" : "[") + format_number(range.min) + ", " +
         format_number(range.max) + "]" + (unit.empty() ? "" : " " + unit);
}

std::string range_problem(const ValueRange& range, double value) {
  const bool above_min = range.min_exclusive ? value > range.min : value >= range.min;
  if (std::isfinite(value) && above_min && value <= range.max) return "";
  const std::string unit = unit_of(range);
  return "must be in " + describe_range(range) + ", got " + format_number(value) + (unit.empty() ? "" : " " + unit);
}

}  // namespace hapscene
