#include "engine/base/type_hint.hpp"

#include <algorithm>
#include <cctype>

#include "engine/base/units.hpp"

namespace hapscene {
namespace {

// A word for an effect, the type it names and what to write (an effect type only where
// the format has that type: 1-D has no box).
struct Synonym {
  std::string_view word;
  std::string_view type;
  std::string_view write;
};
constexpr Synonym kSynonyms[] = {
    {"cage", "box", R"("box" with "solid": "outside")"},
    {"enclosure", "box", R"("box" with "solid": "outside")"},
    {"room", "box", R"("box" with "solid": "outside")"},
    {"arena", "box", R"("box" with "solid": "outside")"},
    {"rectangle", "box", R"("box")"},
    {"rect", "box", R"("box")"},
    {"square", "box", R"("box")"},
    {"block", "box", R"("box")"},
    {"obstacle", "box", R"("box" or "circle" with "solid": "inside")"},
    {"disc", "circle", R"("circle")"},
    {"disk", "circle", R"("circle")"},
    {"ball", "circle", R"("circle")"},
    {"sphere", "circle", R"("circle")"},
    {"cylinder", "circle", R"("circle")"},
    {"shape", "polygon", R"("polygon")"},
    {"triangle", "polygon", R"("polygon")"},
    {"barrier", "wall", R"("wall")"},
    {"floor", "wall", R"("wall")"},
    {"plane", "wall", R"("wall")"},
    {"stop", "wall", R"("wall")"},
    {"elastic", "spring", R"("spring")"},
    {"detent", "spring", R"("spring")"},
    {"friction", "damper", R"("damper" (viscous; a script for Coulomb friction))"},
    {"viscosity", "damper", R"("damper")"},
    {"viscous", "damper", R"("damper")"},
    {"damping", "damper", R"("damper")"},
    {"bumps", "texture", R"("texture")"},
    {"grating", "texture", R"("texture")"},
    {"ridges", "texture", R"("texture")"},
    {"lua", "script", R"("script" with "file": "NAME.lua")"},
};

}  // namespace

std::string effect_type_hint(std::string_view typed, const std::vector<std::string_view>& types) {
  std::string lower(typed.substr(0, kMaxSuggestedNameBytes));
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
  // A plural or a capital letter is the same word ("Walls").
  const std::string singular = lower.ends_with('s') && lower.size() > 3 ? lower.substr(0, lower.size() - 1) : lower;
  const auto known = [&](std::string_view type) { return std::find(types.begin(), types.end(), type) != types.end(); };
  for (const Synonym& synonym : kSynonyms) {
    if ((synonym.word == lower || synonym.word == singular) && known(synonym.type)) {
      return " (did you mean " + std::string(synonym.write) + "?)";
    }
  }
  for (const std::string_view type : types) {
    if (type == lower || type == singular) return " (did you mean \"" + std::string(type) + "\"?)";
  }
  const std::string nearest = nearest_name(typed, types);
  return nearest.empty() ? "" : " (did you mean \"" + nearest + "\"?)";
}

}  // namespace hapscene
