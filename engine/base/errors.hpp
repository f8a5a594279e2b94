#pragma once
// Error types shared by every part. Only load-time code throws; the tick never does.
#include <stdexcept>
#include <string>

namespace hapscene {

// Invalid input: a file, a parameter, a script, an argument. The message names the
// place ("environments/wall.json: /effects/1/stiffness: ..."). The command exits with 2.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Documented exit codes of the `hapscene` command.
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitInvalidInput = 2;

}  // namespace hapscene
