#pragma once
// Running the `hapscene` binary from tests: exit code and both streams.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace hapscene::test {

struct CliOutcome {
  int exit_code{};
  std::string out;
  std::string err;
};

inline std::string slurp_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

// How many times `what` occurs in `text` (overlaps counted): "reported once" checks.
inline std::size_t occurrences(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// Runs `hapscene ARGS` from the folder `working_dir`.
inline CliOutcome run_cli_in(const std::string& working_dir, const std::string& args) {
  static int counter = 0;
  const auto dir = std::filesystem::temp_directory_path();
  const std::string tag = std::to_string(getpid()) + "_h" + std::to_string(counter++);
  const auto out_path = dir / ("hapscene_out_" + tag);
  const auto err_path = dir / ("hapscene_err_" + tag);
  const std::string command = "cd '" + working_dir + "' && '" HAPSCENE_BINARY "' " + args + " >'" +
                              out_path.string() + "' 2>'" + err_path.string() + "' </dev/null";
  const int status = std::system(command.c_str());
  CliOutcome outcome{WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp_file(out_path), slurp_file(err_path)};
  std::filesystem::remove(out_path);
  std::filesystem::remove(err_path);
  return outcome;
}

// Runs `hapscene ARGS` from the source directory.
inline CliOutcome run_cli(const std::string& args) { return run_cli_in(HAPSCENE_SOURCE_DIR, args); }

}  // namespace hapscene::test
