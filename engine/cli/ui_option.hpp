#pragma once
// `run --ui [PORT|HOST:PORT]`: an option whose value is optional, taken from the
// arguments before the others are read (`--ui`, `--ui 8080`, `--ui=0.0.0.0:8080`; a
// following argument is its value only when it looks like a port or HOST:PORT, so
// `run --ui env.json` runs env.json). Given twice, or a bad value, is invalid input.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/base/errors.hpp"
#include "engine/serve/ui_address.hpp"

namespace hapscene {

inline std::optional<UiAddress> take_ui_option(std::vector<std::string>* args, const std::string& command) {
  std::optional<UiAddress> address;
  for (std::size_t i = 0; i < args->size();) {
    const std::string& arg = (*args)[i];
    if (arg != "--ui" && arg.rfind("--ui=", 0) != 0) {
      ++i;
      continue;
    }
    if (address) throw InputError(command + ": --ui is given twice");
    try {
      if (arg == "--ui") {
        const bool has_value = i + 1 < args->size() && looks_like_ui_address((*args)[i + 1]);
        address = has_value ? parse_ui_address((*args)[i + 1]) : UiAddress{};
        args->erase(args->begin() + static_cast<std::ptrdiff_t>(i), args->begin() + static_cast<std::ptrdiff_t>(i + (has_value ? 2 : 1)));
      } else {
        address = parse_ui_address(std::string_view(arg).substr(5));
        args->erase(args->begin() + static_cast<std::ptrdiff_t>(i));
      }
    } catch (const InputError& error) {
      throw InputError(command + ": " + error.what());
    }
  }
  return address;
}

// Whether --NAME (or --NAME=...) is among the arguments.
inline bool option_given(const std::vector<std::string>& args, std::string_view name) {
  const std::string flag = "--" + std::string(name);
  for (const std::string& arg : args) {
    if (arg == flag || arg.rfind(flag + "=", 0) == 0) return true;
  }
  return false;
}

}  // namespace hapscene
