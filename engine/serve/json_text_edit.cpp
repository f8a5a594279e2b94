#include "engine/serve/json_text_edit.hpp"

#include <nlohmann/json.hpp>

#include "engine/base/errors.hpp"

namespace hapscene {
namespace {

// A scanner over well-formed JSON that reports where values and members are.
class Scanner {
 public:
  explicit Scanner(std::string_view text) : text_(text) {}

  void skip_space() {
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\t' || text_[pos_] == '\n' || text_[pos_] == '\r')) {
      ++pos_;
    }
  }
  char peek() const { return pos_ < text_.size() ? text_[pos_] : '\0'; }
  std::size_t pos() const { return pos_; }
  void expect(char c) {
    skip_space();
    if (peek() != c) throw InputError(std::string("JSON edit: expected '") + c + "' at byte " + std::to_string(pos_));
    ++pos_;
  }

  // A string literal's decoded text (escapes that member names use: \" \\ \/ \uXXXX kept as written).
  std::string string_value() {
    skip_space();
    if (peek() != '"') throw InputError("JSON edit: expected a string at byte " + std::to_string(pos_));
    const std::size_t begin = pos_;
    ++pos_;
    while (pos_ < text_.size() && text_[pos_] != '"') pos_ += text_[pos_] == '\\' ? 2 : 1;
    ++pos_;
    return nlohmann::json::parse(text_.substr(begin, pos_ - begin)).get<std::string>();
  }

  // Skips one value; returns its span.
  JsonSpan value() {
    skip_space();
    const std::size_t begin = pos_;
    const char c = peek();
    if (c == '"') {
      (void)string_value();
    } else if (c == '{' || c == '[') {
      const char close = c == '{' ? '}' : ']';
      ++pos_;
      skip_space();
      if (peek() == close) {
        ++pos_;
      } else {
        for (;;) {
          if (c == '{') {
            (void)string_value();
            expect(':');
          }
          (void)value();
          skip_space();
          if (peek() == ',') {
            ++pos_;
            continue;
          }
          expect(close);
          break;
        }
      }
    } else {
      while (pos_ < text_.size() && std::string_view(",}] \t\r\n").find(text_[pos_]) == std::string_view::npos) ++pos_;
    }
    if (pos_ == begin) throw InputError("JSON edit: expected a value at byte " + std::to_string(pos_));
    return {begin, pos_};
  }

  void seek(std::size_t pos) { pos_ = pos; }

 private:
  std::string_view text_;
  std::size_t pos_{};
};

// Where a container's members are, for finding and adding one.
struct Container {
  bool object{};
  std::size_t close{};           // position of '}' or ']'
  std::size_t last_value_end{};  // end of the last member's value (0: empty)
  std::size_t last_key_begin{};  // start of the last member's key
  std::size_t count{};
};

// Looks for `token` in the container starting at the scanner's position; `found` gets
// the member's or element's span.
Container scan_container(Scanner& scanner, const std::string& token, bool* found, JsonSpan* span) {
  Container container;
  scanner.skip_space();
  const char open = scanner.peek();
  if (open != '{' && open != '[') throw InputError("JSON edit: \"" + token + "\" is looked for in a value that is not an object or array");
  container.object = open == '{';
  const char close = container.object ? '}' : ']';
  scanner.expect(open);
  scanner.skip_space();
  *found = false;
  if (scanner.peek() != close) {
    for (;;) {
      std::string key;
      scanner.skip_space();
      const std::size_t key_begin = scanner.pos();
      if (container.object) {
        key = scanner.string_value();
        scanner.expect(':');
      } else {
        key = std::to_string(container.count);
      }
      const JsonSpan member = scanner.value();
      if (!*found && key == token) {
        *found = true;
        *span = member;
      }
      container.last_key_begin = key_begin;
      container.last_value_end = member.end;
      ++container.count;
      scanner.skip_space();
      if (scanner.peek() == ',') {
        scanner.expect(',');
        continue;
      }
      break;
    }
  }
  scanner.skip_space();
  container.close = scanner.pos();
  scanner.expect(close);
  return container;
}

// The text that adds member `key` with `value_json` to an object.
std::string member_insertion(std::string_view text, const Container& object, const std::string& key,
                             const std::string& value_json) {
  const std::string member = json_string_literal(key) + ": " + value_json;
  if (object.count == 0) return member;
  // On a line of its own when the last member is, indented as it is.
  const std::size_t line_start = text.rfind('\n', object.last_key_begin);
  if (line_start != std::string_view::npos) {
    const std::string_view indent = text.substr(line_start + 1, object.last_key_begin - line_start - 1);
    if (indent.find_first_not_of(" \t") == std::string_view::npos) return ",\n" + std::string(indent) + member;
  }
  return ", " + member;
}

}  // namespace

std::string json_string_literal(std::string_view text) { return nlohmann::json(std::string(text)).dump(); }

bool find_json_value(std::string_view text, const std::vector<std::string>& pointer, JsonSpan* span) {
  Scanner scanner(text);
  JsonSpan current = scanner.value();
  for (const std::string& token : pointer) {
    scanner.seek(current.begin);
    bool found = false;
    (void)scan_container(scanner, token, &found, &current);
    if (!found) return false;
  }
  *span = current;
  return true;
}

std::string set_json_value(std::string_view text, const std::vector<std::string>& pointer,
                           const std::string& value_json) {
  if (pointer.empty()) return value_json;
  Scanner scanner(text);
  JsonSpan current = scanner.value();
  for (std::size_t i = 0; i < pointer.size(); ++i) {
    scanner.seek(current.begin);
    bool found = false;
    JsonSpan member;
    const Container container = scan_container(scanner, pointer[i], &found, &member);
    if (found) {
      current = member;
      continue;
    }
    if (!container.object) throw InputError("JSON edit: element " + pointer[i] + " is past the array's end");
    // Absent: add it (wrapping what remains of the path in objects).
    std::string value = value_json;
    for (std::size_t k = pointer.size() - 1; k > i; --k) value = "{" + json_string_literal(pointer[k]) + ": " + value + "}";
    const std::string insertion = member_insertion(text, container, pointer[i], value);
    const std::size_t at = container.count == 0 ? container.close : container.last_value_end;
    std::string out(text);
    out.insert(at, insertion);
    return out;
  }
  std::string out(text);
  out.replace(current.begin, current.end - current.begin, value_json);
  return out;
}

}  // namespace hapscene
