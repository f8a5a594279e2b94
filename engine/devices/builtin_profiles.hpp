#pragma once
// Device profiles shipped in environments/devices, compiled into the engine.
#include <string_view>
#include <vector>

namespace hapscene {

struct BuiltinProfile {
  std::string_view name;       // file name without ".json", e.g. "hapkit3"
  std::string_view json_text;  // the file's text
};

const std::vector<BuiltinProfile>& builtin_profiles();

}  // namespace hapscene
