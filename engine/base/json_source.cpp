#include "engine/base/json_source.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <set>
#include <sstream>
#include <vector>

#include "engine/base/errors.hpp"

namespace hapscene {
namespace {

struct TextPosition {
  std::size_t line{1};
  std::size_t column{1};
};

// Line and column (1-based) of byte `offset` in `text`.
TextPosition position_of(std::string_view text, std::size_t offset) {
  TextPosition position;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++position.line;
      position.column = 1;
    } else {
      ++position.column;
    }
  }
  return position;
}

std::string located(const std::string& name, TextPosition position, const std::string& message) {
  return name + ":" + std::to_string(position.line) + ":" + std::to_string(position.column) +
         ": " + message;
}

// Refuses a number the parser would change before anyone reads it: a whole number past
// 64 bits (it would become a double and lose digits) or past a double's range ("1e400").
// The message echoes the number as written, located at its first character.
void check_number(std::string_view text, std::size_t at, std::string_view token,
                  const std::string& display_name) {
  const bool whole = token.find_first_of(".eE") == std::string_view::npos;
  bool out_of_range = false;
  if (whole) {
    std::int64_t signed_value = 0;
    std::uint64_t unsigned_value = 0;
    const auto as_signed = std::from_chars(token.data(), token.data() + token.size(), signed_value);
    const auto as_unsigned = std::from_chars(token.data(), token.data() + token.size(), unsigned_value);
    out_of_range = as_signed.ec == std::errc::result_out_of_range &&
                   (token.front() == '-' || as_unsigned.ec == std::errc::result_out_of_range);
  } else {
    // Overflow only: a tiny number ("1e-400") reads as 0 like everywhere else.
    const std::string copy(token);
    errno = 0;
    const double value = std::strtod(copy.c_str(), nullptr);
    out_of_range = errno == ERANGE && std::isinf(value);
  }
  if (out_of_range) {
    throw InputError(located(display_name, position_of(text, at),
                             "number out of range: " + std::string(token) +
                                 (whole ? " (whole numbers are limited to 64 bits)" : "")));
  }
}

// One pass over the text before the parser sees it, outside strings: nesting deeper than
// kMaxJsonDepth is refused, and so is every number token check_number refuses.
void check_before_parsing(std::string_view text, const std::string& display_name) {
  int depth = 0;
  bool in_string = false;
  bool escaped = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (c == '{' || c == '[') {
      if (++depth > kMaxJsonDepth) {
        throw InputError(located(display_name, position_of(text, i),
                                 "nesting deeper than " + std::to_string(kMaxJsonDepth) + " levels"));
      }
    } else if (c == '}' || c == ']') {
      --depth;
    } else if (c == '-' || (c >= '0' && c <= '9')) {
      // One number token: sign, digits, fraction, exponent.
      std::size_t end = i + 1;
      while (end < text.size() && (std::isdigit(static_cast<unsigned char>(text[end])) != 0 || text[end] == '.' ||
                                   text[end] == 'e' || text[end] == 'E' || text[end] == '+' || text[end] == '-')) {
        ++end;
      }
      check_number(text, i, text.substr(i, end - i), display_name);
      i = end - 1;
    }
  }
}

// Follows the parser's events to know the JSON pointer of each key, and refuses a key
// given twice in one object.
class DuplicateKeyCheck {
 public:
  bool operator()(int /*depth*/, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    using Event = nlohmann::json::parse_event_t;
    switch (event) {
      case Event::object_start:
      case Event::array_start:
        note_value_start();
        frames_.push_back(Frame{event == Event::array_start, {}, {}, 0});
        break;
      case Event::object_end:
      case Event::array_end:
        frames_.pop_back();
        break;
      case Event::key: {
        Frame& frame = frames_.back();
        frame.key = parsed.get<std::string>();
        if (!frame.keys.insert(frame.key).second) {
          throw InputError(pointer() + ": key \"" + frame.key + "\" appears twice");
        }
        break;
      }
      case Event::value:
        note_value_start();
        break;
    }
    return true;
  }

 private:
  struct Frame {
    bool is_array{};
    std::set<std::string> keys;
    std::string key;
    std::size_t next_index{};
  };

  // A value inside an array advances that array's index.
  void note_value_start() {
    if (!frames_.empty() && frames_.back().is_array) ++frames_.back().next_index;
  }

  std::string pointer() const {
    std::string out;
    for (const Frame& frame : frames_) {
      out = frame.is_array ? json_pointer_append(out, frame.next_index - 1)
                           : json_pointer_append(out, frame.key);
    }
    return out;
  }

  std::vector<Frame> frames_;
};

// nlohmann's message after its "[json.exception...] parse error at line L, column C: ".
std::string parser_message(const std::string& what) {
  const std::size_t column = what.find("column ");
  if (column != std::string::npos) {
    const std::size_t colon = what.find(": ", column);
    if (colon != std::string::npos) return what.substr(colon + 2);
  }
  return what;
}

// What a path that is not a regular file is, for the message.
std::string file_kind(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a named pipe";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// "PATH: cannot open file", with the reason unless the file is simply not there.
std::string cannot_open(const std::string& path, int error) {
  return path + ": cannot open file" +
         (error == ENOENT ? std::string() : " (" + std::string(std::strerror(error)) + ")");
}

std::string too_large(const std::string& path, std::size_t max_bytes) {
  return path + ": file larger than " + std::to_string(max_bytes) + " bytes";
}

}  // namespace

// Never blocks: the path is checked to be a regular file before it is opened, opened
// with O_NONBLOCK (a FIFO swapped in between the check and the open does not wait for a
// writer) and checked again on the open descriptor; the size is checked before reading
// and the read stops one byte past the cap (a file that grows while being read).
std::string read_text_file(const std::string& path, std::size_t max_bytes) {
  struct stat before {};
  if (::stat(path.c_str(), &before) != 0) {
    throw InputError(cannot_open(path, errno));
  }
  if (!S_ISREG(before.st_mode)) {
    throw InputError(path + ": cannot read " + file_kind(before.st_mode) + ", expected a regular file");
  }
  if (static_cast<std::uintmax_t>(before.st_size) > max_bytes) throw InputError(too_large(path, max_bytes));
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) throw InputError(cannot_open(path, errno));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat opened {};
  if (::fstat(fd, &opened) != 0 || !S_ISREG(opened.st_mode)) {
    throw InputError(path + ": cannot read " + file_kind(opened.st_mode) + ", expected a regular file");
  }
  if (static_cast<std::uintmax_t>(opened.st_size) > max_bytes) throw InputError(too_large(path, max_bytes));
  std::string text;
  char buffer[16384];
  for (;;) {
    const ssize_t got = ::read(fd, buffer, sizeof buffer);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) throw InputError(path + ": cannot read file (" + std::strerror(errno) + ")");
    if (got == 0) break;
    text.append(buffer, static_cast<std::size_t>(got));
    if (text.size() > max_bytes) throw InputError(too_large(path, max_bytes));
  }
  return text;
}

void check_readable_file(const std::string& path) {
  struct stat status {};
  if (::stat(path.c_str(), &status) != 0) {
    throw InputError(cannot_open(path, errno));
  }
  if (!S_ISREG(status.st_mode)) {
    throw InputError(path + ": cannot read " + file_kind(status.st_mode) + ", expected a regular file");
  }
}

nlohmann::json parse_json_text(std::string_view text, const std::string& display_name) {
  if (text.size() > kMaxJsonFileBytes) {
    throw InputError(display_name + ": larger than " + std::to_string(kMaxJsonFileBytes) +
                     " bytes");
  }
  check_before_parsing(text, display_name);
  try {
    return nlohmann::json::parse(text, DuplicateKeyCheck{}, /*allow_exceptions=*/true,
                                 /*ignore_comments=*/false);
  } catch (const nlohmann::json::parse_error& error) {
    const std::size_t offset = error.byte > 0 ? error.byte - 1 : 0;
    throw InputError(located(display_name, position_of(text, offset), parser_message(error.what())));
  } catch (const nlohmann::json::out_of_range& error) {
    // A number too large for a double ("1e999"): locate the token the parser names.
    const std::string what = error.what();
    const std::size_t open = what.find('\'');
    const std::size_t close = what.rfind('\'');
    const std::string token = open < close ? what.substr(open + 1, close - open - 1) : "";
    const std::size_t offset = token.empty() ? 0 : text.find(token);
    throw InputError(located(display_name, position_of(text, offset == std::string_view::npos ? 0 : offset),
                             "number out of range: " + token));
  } catch (const InputError& error) {
    throw InputError(display_name + ": " + error.what());
  }
}

nlohmann::json read_json_file(const std::string& path) {
  return parse_json_text(read_text_file(path, kMaxJsonFileBytes), path);
}

std::string json_pointer_append(const std::string& parent, std::string_view key) {
  std::string out = parent + "/";
  for (const char c : key) {
    if (c == '~') out += "~0";
    else if (c == '/') out += "~1";
    else out += c;
  }
  return out;
}

std::string json_pointer_append(const std::string& parent, std::size_t index) {
  return parent + "/" + std::to_string(index);
}

std::string json_type_name(const nlohmann::json& value) {
  if (value.is_boolean()) return "boolean";
  if (value.is_number()) return "number";
  return value.type_name();
}

}  // namespace hapscene
