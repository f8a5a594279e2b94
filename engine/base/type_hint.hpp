#pragma once
// The hint after an unknown effect type, for scenes of any number of axes: a word people
// use for an effect the format names otherwise ("cage" is a box with "solid": "outside")
// first, else the nearest known name by spelling ("wal": "wall").
#include <string>
#include <string_view>
#include <vector>

namespace hapscene {

// " (did you mean \"box\" with \"solid\": \"outside\"?)", " (did you mean \"wall\"?)" or
// "" (nothing close). `types`: the type names the scene's format knows.
std::string effect_type_hint(std::string_view typed, const std::vector<std::string_view>& types);

}  // namespace hapscene
