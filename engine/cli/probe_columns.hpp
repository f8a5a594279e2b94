#pragma once
// The columns of `probe`'s output, one per axis of each quantity: the position, the
// velocity, the force asked and the force commanded. 1-D: x_m, v_m_per_s, force_N,
// output_N; N axes: x_m, y_m, ..., vx_m_per_s, ..., force_x_N, ..., output_x_N, ...
// The CLI's CSV header and Python's Scene.probe dict keys are these.
#include <string>
#include <utility>
#include <vector>

#include "engine/base/axes.hpp"

namespace hapscene {

template <int N>
std::vector<std::string> probe_columns() {
  if constexpr (N == 1) {
    return {"x_m", "v_m_per_s", "force_N", "output_N"};
  } else {
    std::vector<std::string> columns;
    for (const auto& [before, after] : {std::pair{"", "_m"}, std::pair{"v", "_m_per_s"}, std::pair{"force_", "_N"},
                                        std::pair{"output_", "_N"}}) {
      for (int i = 0; i < N; ++i) columns.push_back(std::string(before) + kAxisNames[i] + after);
    }
    return columns;
  }
}

}  // namespace hapscene
