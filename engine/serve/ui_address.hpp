#pragma once
// Where `run --ui` listens: `--ui` (loopback, a free port), `--ui PORT`, `--ui HOST:PORT`
// (HOST a numeric IPv4 address or "localhost"; an IPv6 address in brackets, "[::1]:8080").
#include <string>
#include <string_view>

namespace hapscene {

struct UiAddress {
  std::string host{"127.0.0.1"};
  int port{0};          // 0: a free port, chosen when binding
  bool loopback{true};  // 127.0.0.0/8, ::1 or localhost: else the view warns
};

// Reads the value of --ui ("8080", "0.0.0.0:8080", "[::1]:0"). Throws InputError naming
// --ui and what is wrong ("--ui: port must be a whole number in [0, 65535], got \"99999\"").
UiAddress parse_ui_address(std::string_view text);

// Whether `text` could be the value of --ui rather than the next argument (a file): all
// digits, or something ending in ":DIGITS".
bool looks_like_ui_address(std::string_view text);

}  // namespace hapscene
