#pragma once
// Writing a whole output file (report, figure): an unwritable path is invalid input.
#include <fstream>
#include <string>

#include "engine/core/errors.hpp"

namespace hapscene {

inline void write_output_file(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  if (out) out << text;
  if (!out) throw InputError(path + ": cannot write file");
}

}  // namespace hapscene
