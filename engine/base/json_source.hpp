#pragma once
// Reading JSON files with limits and located errors: malformed JSON reports
// "file:line:column: message", a file over the size or nesting limit is refused before
// parsing, and a key given twice in one object is an error (not "last one wins").
#include <cstddef>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace hapscene {

inline constexpr std::size_t kMaxJsonFileBytes = 1u << 20;  // 1 MiB
inline constexpr int kMaxJsonDepth = 32;

// Reads and parses a JSON file. Throws InputError naming the file.
nlohmann::json read_json_file(const std::string& path);

// Parses JSON text; `display_name` is the file name used in messages. Throws InputError.
nlohmann::json parse_json_text(std::string_view text, const std::string& display_name);

// Reads a whole text file of at most `max_bytes`. Every file hapscene reads goes through
// here: a directory, named pipe, device or socket is refused ("PATH: cannot read a named
// pipe, expected a regular file") and so is a file over the cap, before anything is
// read; it never blocks. Throws InputError naming the file.
std::string read_text_file(const std::string& path, std::size_t max_bytes);

// The same checks without reading: throws InputError unless `path` is a regular file.
void check_readable_file(const std::string& path);

// "/effects/1/stiffness" from a parent pointer and a key (escaping "~" and "/").
std::string json_pointer_append(const std::string& parent, std::string_view key);
std::string json_pointer_append(const std::string& parent, std::size_t index);

// "object", "array", "string", "number", "boolean" or "null".
std::string json_type_name(const nlohmann::json& value);

}  // namespace hapscene
