#include "engine/cli/help_text.hpp"

#include <string>

namespace hapscene {
namespace {

constexpr std::size_t kWidth = 100;         // help lines wrap before this column
constexpr std::size_t kOptionColumn = 28;   // where an option's text starts

// `text` in lines of at most kWidth columns, each after `indent` spaces (the first line's
// indent is `first`, already written by the caller).
std::string wrap(std::string_view text, std::size_t indent, std::size_t first) {
  std::string out;
  std::size_t column = first;
  bool line_empty = true;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t end = std::min(text.find(' ', at), text.size());
    const std::string_view word = text.substr(at, end - at);
    at = end + 1;
    if (word.empty()) continue;
    if (!line_empty && column + 1 + word.size() > kWidth) {
      out += "\n" + std::string(indent, ' ');
      column = indent;
      line_empty = true;
    }
    if (!line_empty) {
      out += ' ';
      ++column;
    }
    for (const char c : word) out += c == '\x1f' ? ' ' : c;
    column += word.size();
    line_empty = false;
  }
  return out + "\n";
}

std::string form_synopsis(const CommandDefinition& form) {
  std::string line = "hapscene " + std::string(form.name);
  if (!form.mode.empty()) line += " --" + std::string(form.mode);
  if (!form.synopsis.empty()) line += " " + std::string(form.synopsis);
  return line;
}

// "--ticks N, --scripts DIR, --no-lua"
std::string option_names(const CommandDefinition& form) {
  std::string names;
  for (const OptionDefinition& option : form.options) {
    if (!names.empty()) names += ", ";
    names += "--" + std::string(option.name);
    // Kept on one line by wrap() (a unit separator, shown as a space).
    if (!option.value_name.empty()) names += "\x1f" + std::string(option.value_name);
  }
  return names;
}

}  // namespace

std::string option_label(const OptionDefinition& option) {
  std::string label = option.short_name != 0 ? std::string("-") + option.short_name + ", " : std::string("    ");
  label += "--" + std::string(option.name);
  if (!option.value_name.empty()) label += " " + std::string(option.value_name);
  return label;
}

std::string option_details(const OptionDefinition& option) {
  std::string details;
  if (!option.default_text.empty()) details += "default " + std::string(option.default_text);
  std::string range;
  if (option.quantity != nullptr) range = describe_range(*option.quantity);
  if (option.whole != nullptr) {
    range = "[" + std::to_string(option.whole->min) + ", " + std::to_string(option.whole->max) + "]";
  }
  if (!range.empty()) details += std::string(details.empty() ? "" : "; ") + "range " + range;
  return details;
}

std::string top_level_usage() {
  std::string out = "hapscene: a data-driven haptic rendering engine\n\n";
  out += "usage: hapscene COMMAND [ARGS...]\n";
  out += "       hapscene COMMAND --help, hapscene help COMMAND: the command's options, defaults and examples\n\n";
  out += "commands:\n";
  constexpr std::size_t kSummaryColumn = 44;
  const auto entry = [&](const std::string& left, std::string_view summary, const std::string& options) {
    out += "  " + left;
    if (left.size() + 2 < kSummaryColumn - 1) {
      out += std::string(kSummaryColumn - 2 - left.size(), ' ');
    } else {
      out += "\n" + std::string(kSummaryColumn, ' ');
    }
    out += wrap(summary, kSummaryColumn, kSummaryColumn);
    if (!options.empty()) out += std::string(kSummaryColumn, ' ') + wrap(options, kSummaryColumn, kSummaryColumn);
  };
  for (const CommandDefinition& form : command_definitions()) {
    entry(form_synopsis(form), form.summary, option_names(form));
  }
  for (const BuiltinCommand& builtin : builtin_commands()) {
    entry("hapscene " + std::string(builtin.name) + (builtin.synopsis.empty() ? "" : " ") +
              std::string(builtin.synopsis),
          builtin.summary, "");
  }
  out += "  hapscene --version, -V\n\n";
  out += wrap(kValuesNote, 0, 0);
  out += wrap(kExitNote, 0, 0);
  return out;
}

std::string command_help(std::string_view command) {
  std::string out;
  bool first = true;
  for (const CommandDefinition& form : command_definitions()) {
    if (form.name != command) continue;
    out += (first ? "usage: " : "\n       ") + form_synopsis(form);
    first = false;
  }
  if (first) return {};
  out += "\n";
  for (const CommandDefinition& form : command_definitions()) {
    if (form.name != command) continue;
    out += "\n";
    if (!form.mode.empty()) out += "--" + std::string(form.mode) + ": " + std::string(form.summary) + "\n";
    out += wrap(form.description, 0, 0);
    out += "\noptions" + (form.mode.empty() ? std::string() : " of --" + std::string(form.mode)) + ":\n";
    if (form.options.empty()) out += "  (none)\n";
    for (const OptionDefinition& option : form.options) {
      const std::string label = "  " + option_label(option);
      std::string text(option.help);
      const std::string details = option_details(option);
      if (!details.empty()) text += " (" + details + ")";
      out += label;
      if (label.size() + 2 <= kOptionColumn) {
        out += std::string(kOptionColumn - label.size(), ' ');
      } else {
        out += "\n" + std::string(kOptionColumn, ' ');
      }
      out += wrap(text, kOptionColumn, kOptionColumn);
    }
    if (form.mode.empty()) out += "  -h, --help" + std::string(kOptionColumn - 12, ' ') + "this text\n";
    if (!form.examples.empty()) {
      out += "\nexamples:\n";
      for (const std::string_view example : form.examples) out += "  hapscene " + std::string(example) + "\n";
    }
  }
  out += "\n" + wrap(kValuesNote, 0, 0);
  out += wrap(kExitNote, 0, 0);
  return out;
}

}  // namespace hapscene
