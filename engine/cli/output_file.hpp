#pragma once
// Writing a whole output file (report, figure, profile). A path that cannot be opened is invalid
// input (InputError, exit code 2); a write, flush or close that fails afterwards (a full
// disk, /dev/full) is a failure of the command (std::runtime_error, exit code 1). Both
// name the file.
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "engine/base/errors.hpp"
#include "engine/base/file_replace.hpp"

namespace hapscene {

// "PATH: write failed: No space left on device".
inline std::string write_failed_message(const std::string& path, int error_number) {
  return path + ": write failed: " + (error_number != 0 ? std::strerror(error_number) : "unknown error");
}

// Replaced whole (engine/base/file_replace.hpp): a reader never sees half a report, and a
// link planted next to it is not written through; /dev/null or /dev/stdout is written
// through as it is.
inline void write_output_file(const std::string& path, const std::string& text) {
  const FileWriteOutcome outcome = replace_file(path, text, SpecialPath::write_through);
  if (outcome.failed == FileWriteStep::open) throw InputError(path + ": cannot write file");
  if (!outcome.ok()) throw std::runtime_error(write_failed_message(path, outcome.error_number));
}

// Checks a command's output files before it does any work: each must lie in an existing
// folder, must not be a folder, and must not be the same file as one of `inputs` (an
// environment, its device profile) or as another output ("--log env.json" would
// overwrite the environment). `outputs` pairs an option name with its path. Returns the
// first problem ("--log environments/wall.json: is an input file of this command"), or
// "" when there is none.
inline std::string output_path_problem(const std::vector<std::pair<std::string, std::string>>& outputs,
                                       const std::vector<std::string>& inputs) {
  namespace fs = std::filesystem;
  const auto canonical = [](const std::string& path) {
    std::error_code error;
    const fs::path resolved = fs::weakly_canonical(fs::path(path), error);
    return error ? fs::absolute(fs::path(path), error).lexically_normal() : resolved;
  };
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const auto& [option, path] = outputs[i];
    const std::string named = "--" + option + " " + path;
    std::error_code error;
    const fs::path resolved = canonical(path);
    if (fs::is_directory(resolved, error)) return named + ": is a folder, expected a file name";
    const fs::path folder = resolved.parent_path();
    if (!folder.empty() && !fs::is_directory(folder, error)) return named + ": no folder " + folder.string();
    for (const std::string& input : inputs) {
      if (canonical(input) == resolved) return named + ": is an input file of this command (" + input + ")";
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (canonical(outputs[j].second) == resolved) return named + ": is also given to --" + outputs[j].first;
    }
  }
  return "";
}

}  // namespace hapscene
