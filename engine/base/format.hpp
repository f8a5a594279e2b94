#pragma once
// printf-style formatting into a std::string, for report lines and messages (not for the
// tick: it allocates). Lines longer than 511 characters are cut. And printable(): text
// from files and scripts made safe to print; split_names() for the options that take a
// comma-separated list.
#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

namespace hapscene {

inline std::string printf_string(const char* pattern, auto... values) {
  char text[512];
  std::snprintf(text, sizeof text, pattern, values...);
  return text;
}

}  // namespace hapscene

namespace hapscene {

// Text that comes from files, scripts or the command line (names, paths, JSON strings,
// script errors and log() messages), made safe to print: control characters (C0, DEL and
// the C1 range; not the tab, which print() puts between values) and bytes that are not
// valid UTF-8 become escapes ("\n", "\r", "\x1b", "\x00", "\xc2\x9b"), so such text can never start a new line (and forge a
// "PASS" line), move the cursor, recolour a terminal or cut a message short. Printable
// ASCII and valid UTF-8 are kept as written, so the result of printable text is itself,
// and escaping twice changes nothing.
//
// write_printable writes into out (at most out_size - 1 bytes and a NUL; an escape is never
// split) and returns the length written. No allocation: script faults use it in the tick.
inline std::size_t write_printable(std::string_view text, char* out, std::size_t out_size) noexcept {
  if (out_size == 0) return 0;
  static constexpr char kHex[] = "0123456789abcdef";
  std::size_t length = 0;
  const auto put = [&](const char* piece, std::size_t n) {
    if (length + n > out_size - 1) return false;
    for (std::size_t k = 0; k < n; ++k) out[length++] = piece[k];
    return true;
  };
  const auto put_escaped_byte = [&](unsigned char byte) {
    const char* named = byte == '\n' ? "\\n" : byte == '\r' ? "\\r" : nullptr;
    if (named != nullptr) return put(named, 2);
    const char escape[4] = {'\\', 'x', kHex[byte >> 4], kHex[byte & 0xF]};
    return put(escape, 4);
  };
  const auto byte_at = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  for (std::size_t i = 0; i < text.size();) {
    const unsigned char lead = byte_at(i);
    if ((lead >= 0x20 && lead < 0x7F) || lead == '\t') {
      if (!put(&text[i], 1)) break;
      ++i;
      continue;
    }
    // The length of a valid UTF-8 sequence starting here (0: not one).
    std::size_t n = 0;
    unsigned char low = 0x80, high = 0xBF;  // the second byte's range
    if (lead >= 0xC2 && lead <= 0xDF) n = 2;
    else if (lead >= 0xE0 && lead <= 0xEF) n = 3, low = lead == 0xE0 ? 0xA0 : 0x80, high = lead == 0xED ? 0x9F : 0xBF;
    else if (lead >= 0xF0 && lead <= 0xF4) n = 4, low = lead == 0xF0 ? 0x90 : 0x80, high = lead == 0xF4 ? 0x8F : 0xBF;
    bool valid = n > 0 && i + n <= text.size();
    for (std::size_t k = 1; valid && k < n; ++k) {
      const unsigned char next = byte_at(i + k);
      valid = k == 1 ? next >= low && next <= high : next >= 0x80 && next <= 0xBF;
    }
    const bool c1_control = valid && lead == 0xC2 && byte_at(i + 1) <= 0x9F;
    if (valid && !c1_control) {
      if (!put(&text[i], n)) break;
      i += n;
    } else if (c1_control) {
      if (!put_escaped_byte(lead) || !put_escaped_byte(byte_at(i + 1))) break;
      i += 2;
    } else {
      if (!put_escaped_byte(lead)) break;
      ++i;
    }
  }
  out[length] = '\0';
  return length;
}

inline std::string printable(std::string_view text) {
  // At most four bytes out per byte in, plus the NUL.
  std::string out(4 * text.size() + 1, '\0');
  out.resize(write_printable(text, out.data(), out.size()));
  return out;
}

// The names of a comma-separated list, as written ("a,,b": "a", "", "b"; "": one empty name).
inline std::vector<std::string> split_names(std::string_view list) {
  std::vector<std::string> names;
  std::size_t begin = 0;
  while (begin <= list.size()) {
    const std::size_t end = std::min(list.find(',', begin), list.size());
    names.emplace_back(list.substr(begin, end - begin));
    begin = end + 1;
  }
  return names;
}

}  // namespace hapscene
