// `hapscene new KIND NAME [--device PROFILE] [--force]`: starts a user's own environment,
// script or test spec from a commented template (engine/cli/new_templates.hpp), named
// for what they asked, and says what to run next. It never overwrites a file unless told
// to (--force), and never follows a symbolic link where it writes.
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"
#include "engine/cli/arguments.hpp"
#include "engine/cli/commands.hpp"
#include "engine/cli/new_templates.hpp"
#include "engine/cli/standard_output.hpp"
#include "engine/base/units.hpp"
#include "engine/devices/planar/planar_profile.hpp"
#include "engine/load/environment.hpp"

namespace hapscene {
namespace {

const NewKind* find_kind(const std::string& name) {
  for (const NewKind& kind : new_kinds()) {
    if (kind.name == name) return &kind;
  }
  return nullptr;
}

std::string kind_list() {
  std::string list;
  for (const NewKind& kind : new_kinds()) list += (list.empty() ? "" : ", ") + std::string(kind.name);
  return list;
}

// NAME without the ending the user may have typed ("my_wall.json" -> "my_wall").
std::string stem_of(std::string name) {
  for (const std::string_view ending : {".test.json", ".json", ".lua"}) {
    if (name.size() > ending.size() && name.ends_with(ending)) return name.substr(0, name.size() - ending.size());
  }
  return name;
}

// Writes a new file: created exclusively unless `overwrite`, never through a symbolic
// link (O_NOFOLLOW on the last part; an existing link is refused, not followed).
void write_new_file(const std::string& path, const std::string& text, bool overwrite) {
  const int flags = O_WRONLY | O_CREAT | O_NOFOLLOW | O_CLOEXEC | (overwrite ? O_TRUNC : O_EXCL);
  const int fd = ::open(path.c_str(), flags, 0644);
  if (fd < 0) {
    const int error = errno;
    if (error == EEXIST) throw InputError(path + ": exists already (--force overwrites it)");
    if (error == ELOOP) throw InputError(path + ": is a symbolic link; hapscene new does not write through one");
    throw InputError(path + ": cannot create file: " + std::strerror(error));
  }
  std::size_t written = 0;
  while (written < text.size()) {
    const ssize_t n = ::write(fd, text.data() + written, text.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int error = errno;
      ::close(fd);
      throw std::runtime_error(path + ": write failed: " + std::strerror(error));
    }
    written += static_cast<std::size_t>(n);
  }
  if (::close(fd) != 0) throw std::runtime_error(path + ": write failed: " + std::strerror(errno));
}

// Where a 2-DOF template's shape goes: in the middle of the device's workspace box across,
// and half-way from the handle's home to the box's farther edge along y, small enough
// (a fifth of the box, and 0.4 of the way to that edge) that the handle starts outside it.
// The environment names a profile file by its path from the environment's own folder.
PlanarPlacement placement_on(const std::string& device, const std::string& stem) {
  const PlanarProfile profile = load_planar_profile(device, ".");
  const PlanarWorkspace& workspace = profile.limits.workspace;
  PlanarPlacement placement;
  placement.device = device;
  if (device.find('/') != std::string::npos || device.ends_with(".json")) {
    const std::filesystem::path folder = std::filesystem::absolute(std::filesystem::path(stem)).parent_path();
    placement.device = std::filesystem::absolute(device).lexically_relative(folder).string();
  }
  const Vec2 low = workspace.box_min_m, high = workspace.box_max_m;
  const double home_y_m = profile.home_m[1];
  const double far_edge_y_m = home_y_m - low[1] >= high[1] - home_y_m ? low[1] : high[1];
  placement.center_m[0] = 0.5 * (low[0] + high[0]);
  placement.center_m[1] = 0.5 * (home_y_m + far_edge_y_m);
  placement.half_size_m[0] = 0.2 * (high[0] - low[0]);
  placement.half_size_m[1] = std::min(0.2 * (high[1] - low[1]), 0.4 * std::abs(far_edge_y_m - home_y_m));
  return placement;
}

}  // namespace

int new_command(std::vector<std::string> args) {
  Arguments arguments(std::move(args), "hapscene new");
  const std::optional<std::string> device = arguments.take_value("device");
  const bool overwrite = arguments.take_flag("force");
  const std::vector<std::string> positionals = arguments.positionals();
  if (positionals.size() != 2) {
    arguments.fail("expected KIND NAME, e.g. hapscene new wall my_wall (kinds: " + kind_list() + ")");
  }
  const NewKind* kind = find_kind(positionals[0]);
  if (kind == nullptr) {
    const std::string nearest = nearest_name(positionals[0], [] {
      std::vector<std::string_view> names;
      for (const NewKind& each : new_kinds()) names.push_back(each.name);
      return names;
    }());
    arguments.fail("unknown kind \"" + printable(positionals[0]) + "\"" +
                   (nearest.empty() ? "" : " (did you mean \"" + nearest + "\"?)") + "; kinds: " + kind_list());
  }
  const std::string stem = stem_of(positionals[1]);
  const std::string name = std::filesystem::path(stem).filename().string();
  if (name.empty() || name == "." || name == "..") arguments.fail("NAME \"" + printable(positionals[1]) + "\" names no file");
  if (device && kind->axes != 2) arguments.fail("--device: only for the 2-DOF kinds (box, circle, planar-script)");

  // What to write: (path, text) pairs, all refused before any is written.
  std::vector<std::pair<std::string, std::string>> files;
  std::string next;
  if (kind->name == "spec") {
    // The environment beside the spec: NAME.json, else NAME.lua.
    const std::string environment = std::filesystem::exists(stem + ".json") ? stem + ".json" : stem + ".lua";
    if (!std::filesystem::exists(environment)) {
      arguments.fail("no " + stem + ".json or " + stem + ".lua to write a spec for (hapscene new KIND " + stem +
                     " starts one)");
    }
    // Which dimension: a 2-DOF environment names a planar device; a probe says it as well,
    // but the spec's own description is all that differs.
    const std::string environment_file = std::filesystem::path(environment).filename().string();
    const int axes = environment.ends_with(".json") ? environment_axes(environment) : 1;
    files.push_back({stem + ".test.json", spec_template(environment_file, axes)});
    next = "hapscene test " + stem + ".test.json";
  } else {
    const PlanarPlacement planar = kind->axes == 2 ? placement_on(device.value_or("haplink"), stem) : PlanarPlacement{};
    if (kind->name == "script") {
      files.push_back({stem + ".lua", script_template(1, name, planar)});
      next = "hapscene validate " + stem + ".lua   then   hapscene run " + stem + ".lua";
    } else if (kind->name == "planar-script") {
      files.push_back({stem + ".lua", script_template(2, name, planar)});
      files.push_back({stem + ".json", environment_template(kind->name, name, planar)});
      next = "hapscene validate " + stem + ".json   then   hapscene run " + stem + ".json";
    } else {
      files.push_back({stem + ".json", environment_template(kind->name, name, planar)});
      next = "hapscene validate " + stem + ".json   then   hapscene run " + stem + ".json";
    }
  }
  if (!overwrite) {
    for (const auto& [path, text] : files) {
      std::error_code error;
      if (std::filesystem::symlink_status(path, error).type() != std::filesystem::file_type::not_found) {
        throw InputError(path + ": exists already (--force overwrites it)");
      }
    }
  }
  for (const auto& [path, text] : files) {
    write_new_file(path, text, overwrite);
    print_out("wrote %s\n", printable(path).c_str());
  }
  print_out("%s: %s\nnext:  %s\n", std::string(kind->name).c_str(), std::string(kind->summary).c_str(),
            printable(next).c_str());
  if (kind->name != "spec") print_out("       hapscene new spec %s   (a test spec for it)\n", printable(stem).c_str());
  return kExitOk;
}

}  // namespace hapscene
