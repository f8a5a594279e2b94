#pragma once
// The names of per-axis columns (CSV headers, Python dict keys), written once for every N:
// a quantity named BEFORE + axis + AFTER has one column per axis ("force_x_N",
// "force_y_N"); with one axis the axis name is dropped ("force_N", "v_m_per_s"), except
// for the position, whose BEFORE is empty ("x_m"). Motors are numbered from 1 ("duty_1");
// a single motor's columns have no number ("duty").
#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/base/axes.hpp"

namespace hapscene {

// The column of axis `i` of the quantity BEFORE..AFTER.
template <int N>
std::string axis_column(std::string_view before, int i, std::string_view after) {
  if (N == 1 && !before.empty()) {
    if (before.ends_with('_')) before.remove_suffix(1);
    return std::string(before) + std::string(after);
  }
  return std::string(before) + kAxisNames[i] + std::string(after);
}

// Every axis of each quantity {BEFORE, AFTER}, quantity after quantity.
template <int N>
std::vector<std::string> axis_columns(std::initializer_list<std::pair<std::string_view, std::string_view>> quantities) {
  std::vector<std::string> columns;
  for (const auto& [before, after] : quantities) {
    for (int i = 0; i < N; ++i) columns.push_back(axis_column<N>(before, i, after));
  }
  return columns;
}

// The columns of motor `motor` (from 0) named NAME: "NAME_1", ..., or "NAME" for one motor.
template <int N>
std::string motor_column(std::string_view name, int motor) {
  return N == 1 ? std::string(name) : std::string(name) + "_" + std::to_string(motor + 1);
}

// The handle's state, one column per axis of each quantity: the position, the velocity,
// the force the effects asked for and the force commanded after safety. 1-D: x_m,
// v_m_per_s, force_N, output_N; N axes: x_m, y_m, ..., vx_m_per_s, ..., force_x_N, ...,
// output_x_N, ... `probe`'s CSV header, Python's Scene.probe keys and the first columns of
// the run's log (telemetry_log.hpp) are these.
template <int N>
std::vector<std::string> handle_state_columns() {
  return axis_columns<N>({{"", "_m"}, {"v", "_m_per_s"}, {"force_", "_N"}, {"output_", "_N"}});
}

// "a,b,c": columns joined into a CSV header line (without the newline).
inline std::string csv_header_line(const std::vector<std::string>& columns) {
  std::string line;
  for (const std::string& column : columns) line += (line.empty() ? "" : ",") + column;
  return line;
}

}  // namespace hapscene
