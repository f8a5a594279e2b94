#pragma once
// Reading a whole number from text, whole: every character must be a decimal digit
// ("10x", "-1", "+3", " 7", "7.5", "1e3" and "" are not whole numbers). The one reader of
// integers from text in the engine; callers add their range and their message.
#include <charconv>
#include <cstdint>
#include <string_view>

namespace hapscene {

enum class WholeNumberRead : std::uint8_t { ok, not_whole, too_large };

// Writes *value only when it returns ok; too_large: digits only, past 2^64 - 1.
inline WholeNumberRead read_whole_number(std::string_view text, std::uint64_t* value) noexcept {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string_view::npos) {
    return WholeNumberRead::not_whole;
  }
  std::uint64_t read = 0;
  const char* const end = text.data() + text.size();
  const auto [stop, ec] = std::from_chars(text.data(), end, read);
  if (ec == std::errc::result_out_of_range) return WholeNumberRead::too_large;
  if (ec != std::errc() || stop != end) return WholeNumberRead::not_whole;
  *value = read;
  return WholeNumberRead::ok;
}

}  // namespace hapscene
