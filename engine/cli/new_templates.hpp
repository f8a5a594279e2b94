#pragma once
// The templates `hapscene new` starts a user's files from: an environment of one built-in
// effect, a Lua script (1-DOF or 2-DOF), and a test spec, each with its guidance in the
// file (Lua comments; a JSON file's "description"). Every template loads, validates and
// passes its own spec as written (tests/cli/new_command_test.cpp).
#include <string>
#include <string_view>
#include <vector>

#include "engine/base/axes.hpp"

namespace hapscene {

// One kind `hapscene new` makes.
struct NewKind {
  std::string_view name;     // "wall"
  int axes;                  // 1 or 2
  std::string_view summary;  // "a wall with a solid side (1-DOF)"
};

// Every kind, in the order the help lists them.
const std::vector<NewKind>& new_kinds();

// Where a 2-DOF template puts its shape (engine/cli/new_command.cpp chooses it from the
// device's profile so that the handle starts outside it).
struct PlanarPlacement {
  std::string device;  // the profile as the environment names it ("haplink", "../my.json")
  Vec2 center_m{};
  Vec2 half_size_m{};  // the shape's half extent per axis
};

// The file texts. `name` is the environment's name (the file's stem).
std::string environment_template(std::string_view kind, const std::string& name, const PlanarPlacement& planar);
std::string script_template(int axes, const std::string& name, const PlanarPlacement& planar);
// A spec for `environment_file` (a path relative to the spec's folder) of `axes` axes.
std::string spec_template(const std::string& environment_file, int axes);

}  // namespace hapscene
