#pragma once
// Error types shared by every part. Only load-time code throws; the tick never does.
#include <stdexcept>
#include <string>
#include <string_view>

#include "engine/base/format.hpp"

namespace hapscene {

// Invalid input: a file, a parameter, a script, an argument. The message names the
// place ("environments/wall.json: /effects/1/stiffness: ..."). The command exits with 2.
// The message quotes text from the input (keys, strings, paths, script errors), so it is
// kept in printable form (engine/base/format.hpp): a "\n" in a JSON string cannot forge
// an output line, and a NUL cannot cut the message short.
class InputError : public std::runtime_error {
 public:
  explicit InputError(std::string_view message) : std::runtime_error(printable(message)) {}
};

// Documented exit codes of the `hapscene` command.
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;
inline constexpr int kExitInvalidInput = 2;

}  // namespace hapscene
