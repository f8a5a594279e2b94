#pragma once
// Editing one value of a JSON text in place, so a file saved from the live view keeps
// its layout: every byte outside the edited value stays as written (key order, spacing,
// comments of style, the units of other values). Only well-formed JSON is edited (the
// text was loaded before); the scanner follows RFC 8259.
#include <string>
#include <string_view>
#include <vector>

namespace hapscene {

// Where a value sits in a JSON text: [begin, end) of its bytes.
struct JsonSpan {
  std::size_t begin{};
  std::size_t end{};
};

// The span of the value at `pointer` (RFC 6901 tokens, already split and unescaped:
// {"effects", "0", "stiffness"}), or false when some member or element is absent.
bool find_json_value(std::string_view text, const std::vector<std::string>& pointer, JsonSpan* span);

// The text with the value at `pointer` set to `value_json` (a JSON value as text). When
// the last token names a member the object lacks, it is added after the object's last
// member (on a line of its own, indented like that member, when the object spreads over
// lines); when the member before it is missing too (an effect without "params"), that
// member is added as an object holding it. Throws InputError when the path leads through
// something that is not an object or array, or to an element past an array's end.
std::string set_json_value(std::string_view text, const std::vector<std::string>& pointer,
                           const std::string& value_json);

// A JSON string literal for `text` (quoted and escaped).
std::string json_string_literal(std::string_view text);

}  // namespace hapscene
