#pragma once
// printf-style formatting into a std::string, for report lines and messages (not for the
// tick: it allocates). Lines longer than 511 characters are cut.
#include <cstdio>
#include <string>

namespace hapscene {

inline std::string printf_string(const char* pattern, auto... values) {
  char text[512];
  std::snprintf(text, sizeof text, pattern, values...);
  return text;
}

}  // namespace hapscene
