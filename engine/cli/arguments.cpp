#include "engine/cli/arguments.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "engine/base/errors.hpp"
#include "engine/base/object_reader.hpp"
#include "engine/base/whole_number.hpp"
#include "engine/cli/command_definitions.hpp"

namespace hapscene {
namespace {

std::string unit_of(const QuantityOption& option) {
  return std::string(option.unit.empty() ? si_unit(option.quantity) : option.unit);
}

std::string with_unit(double value, const std::string& unit) {
  return format_number(value) + (unit.empty() ? "" : " " + unit);
}

std::string long_form(const OptionDefinition& option) { return "--" + std::string(option.name); }

// "--duration 3 s": a bare number followed by a word that can only be its unit ("s",
// "mm", "N/m"; also a misspelt one such as "sec", which the quantity's parser then names).
// A word with a dot or one that is an existing path is a file, as before.
bool is_unit_word(const std::string& word) {
  if (word.empty() || word.size() > 12 || !std::isalpha(static_cast<unsigned char>(word[0]))) return false;
  for (const char c : word) {
    const auto u = static_cast<unsigned char>(c);
    if (!std::isalnum(u) && c != '/' && c != '*' && c != '^' && u < 0x80) return false;
  }
  std::error_code error;
  return !std::filesystem::exists(word, error);
}

bool is_bare_number(const std::string& text) {
  const QuantityParse parsed = parse_quantity(text);
  return parsed.ok && parsed.quantity == Quantity::dimensionless && text.find_first_of(" \t") == std::string::npos;
}

}  // namespace

Arguments::Arguments(std::vector<std::string> args, std::string command) : command_(std::move(command)) {
  const std::string name = command_.starts_with("hapscene ") ? command_.substr(9) : command_;
  form_ = find_command_form(name, args);
  if (form_ == nullptr) throw std::logic_error(command_ + ": not in engine/cli/command_definitions.cpp");
  parse(args);
}

void Arguments::parse(const std::vector<std::string>& args) {
  const std::span<const OptionDefinition> options = form_->options;
  const auto by_name = [&](std::string_view name) -> const OptionDefinition* {
    for (const OptionDefinition& option : options) {
      if (option.name == name) return &option;
    }
    return nullptr;
  };
  const auto by_short = [&](char c) -> const OptionDefinition* {
    for (const OptionDefinition& option : options) {
      if (option.short_name != 0 && option.short_name == c) return &option;
    }
    return nullptr;
  };
  // "-x" names an option when x is a letter; "-5mm" and "-0.5" are values or positionals.
  const auto is_short_option = [](const std::string& arg) {
    return arg.size() >= 2 && arg[0] == '-' && std::isalpha(static_cast<unsigned char>(arg[1]));
  };
  const auto is_long_option = [](const std::string& arg) { return arg.starts_with("--") && arg.size() > 2; };

  bool options_ended = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (options_ended) {
      positionals_.push_back(arg);
      continue;
    }
    if (arg == "--") {
      options_ended = true;
      continue;
    }
    const OptionDefinition* option = nullptr;
    std::optional<std::string> inline_value;
    std::string written;  // the option as given, for messages
    if (is_long_option(arg)) {
      const std::size_t equals = arg.find('=');
      const std::string name = arg.substr(2, equals == std::string::npos ? std::string::npos : equals - 2);
      if (equals != std::string::npos) inline_value = arg.substr(equals + 1);
      written = "--" + name;
      if (!form_->mode.empty() && name == form_->mode) {
        if (inline_value) fail(written + " takes no value, got \"" + arg + "\"");
        if (mode_given_) fail(written + " is given twice");
        mode_given_ = true;
        continue;
      }
      option = by_name(name);
      if (option == nullptr) fail(unknown_option_message(written));
    } else if (is_short_option(arg)) {
      written = arg.substr(0, 2);
      option = by_short(arg[1]);
      if (option == nullptr) fail(unknown_option_message(written));
      if (arg.size() > 2) inline_value = arg.substr(arg[2] == '=' ? 3 : 2);
    } else {
      positionals_.push_back(arg);
      continue;
    }

    const std::string name = long_form(*option);
    for (const Given& given : given_) {
      if (given.option == option) fail(name + " is given twice");
    }
    if (option->value_name.empty()) {
      if (inline_value) fail(name + " takes no value, got \"" + arg + "\"");
      given_.push_back({option, "", false});
      continue;
    }
    std::string value;
    if (inline_value) {
      value = *inline_value;
    } else {
      if (i + 1 >= args.size()) fail(name + " needs a value");
      value = args[++i];
      // "--log --quiet" forgot the file name; it would otherwise write a file called
      // "--quiet" (a value that starts with "--" is given as --log=--quiet).
      if (is_long_option(value) || (is_short_option(value) && value.size() == 2 && by_short(value[1]) != nullptr)) {
        fail(name + " needs a value, got the option " + value);
      }
      if (option->quantity != nullptr && i + 1 < args.size() && is_bare_number(value) && is_unit_word(args[i + 1])) {
        value += " " + args[++i];
      }
    }
    given_.push_back({option, value, false});
  }
}

std::string Arguments::unknown_option_message(const std::string& written) const {
  std::string message = "unknown option " + written;
  const std::string name = written.starts_with("--") ? written.substr(2) : std::string();
  // An option of another form of the command (bench --seconds with --stress).
  if (!name.empty()) {
    for (const CommandDefinition& other : command_definitions()) {
      if (other.name != form_->name || &other == form_) continue;
      for (const OptionDefinition& option : other.options) {
        if (option.name != name) continue;
        const std::string where = other.mode.empty() ? std::string() : " --" + std::string(other.mode);
        const std::string here = form_->mode.empty() ? std::string() : " --" + std::string(form_->mode);
        return message + " for hapscene " + std::string(form_->name) + here + " (an option of hapscene " +
               std::string(other.name) + where + ")";
      }
    }
  }
  std::vector<std::string> candidates;
  for (const OptionDefinition& option : form_->options) {
    if (written.starts_with("--")) candidates.push_back("--" + std::string(option.name));
    else if (option.short_name != 0) candidates.push_back(std::string("-") + option.short_name);
  }
  if (written.starts_with("--")) {
    for (const CommandDefinition& other : command_definitions()) {
      if (other.name == form_->name && !other.mode.empty()) candidates.push_back("--" + std::string(other.mode));
    }
  }
  const std::string suggestion = written.size() > 3 ? nearest_name(written, candidates) : std::string();
  if (!suggestion.empty()) message += " (did you mean " + suggestion + "?)";
  return message;
}

void Arguments::fail(const std::string& message) const {
  throw InputError(command_ + ": " + message);
}

Arguments::Given* Arguments::find_given(std::string_view name, bool flag) {
  const OptionDefinition* defined = nullptr;
  for (const OptionDefinition& option : form_->options) {
    if (option.name == name) defined = &option;
  }
  if (defined == nullptr || defined->value_name.empty() != flag) {
    throw std::logic_error(command_ + ": the code reads --" + std::string(name) + (flag ? " as a flag" : " with a value") +
                           ", which engine/cli/command_definitions.cpp does not define so for this command");
  }
  for (Given& given : given_) {
    if (given.option == defined && !given.taken) return &given;
  }
  return nullptr;
}

std::optional<std::string> Arguments::take_value(std::string_view name) {
  Given* given = find_given(name, false);
  if (given == nullptr) return std::nullopt;
  given->taken = true;
  return given->value;
}

std::optional<double> Arguments::take(const QuantityOption& option) {
  const std::optional<std::string> text = take_value(option.name);
  if (!text) return std::nullopt;
  return parse_option_quantity(*text, option, command_ + ": --" + std::string(option.name));
}

std::optional<std::uint64_t> Arguments::take(const WholeOption& option) {
  const std::optional<std::string> text = take_value(option.name);
  if (!text) return std::nullopt;
  return parse_whole_number(*text, option, command_ + ": --" + std::string(option.name));
}

bool Arguments::take_flag(std::string_view name) {
  // A form's own mode flag, or another form's (not given, since it would select that form).
  for (const CommandDefinition& other : command_definitions()) {
    if (other.name != form_->name || other.mode != name) continue;
    if (&other != form_) return false;
    const bool given = mode_given_ && !mode_taken_;
    mode_taken_ = true;
    return given;
  }
  Given* given = find_given(name, true);
  if (given == nullptr) return false;
  given->taken = true;
  return true;
}

std::vector<std::string> Arguments::positionals() const {
  for (const Given& given : given_) {
    if (!given.taken) {
      throw std::logic_error(command_ + ": --" + std::string(given.option->name) +
                             " is defined in engine/cli/command_definitions.cpp but the command does not read it");
    }
  }
  return positionals_;
}

std::string describe_range(const QuantityOption& option) {
  const std::string unit = unit_of(option);
  return std::string(option.min_exclusive ? "(" : "[") + format_number(option.min) + ", " +
         format_number(option.max) + "]" + (unit.empty() ? "" : " " + unit);
}

double parse_option_quantity(const std::string& text, const QuantityOption& option, const std::string& what) {
  const QuantityParse parsed = parse_quantity_as(text, option.quantity);
  if (!parsed.ok) throw InputError(what + ": " + parsed.error);
  const double value = parsed.value_si;
  const bool above_min = option.min_exclusive ? value > option.min : value >= option.min;
  if (!std::isfinite(value) || !above_min || value > option.max) {
    throw InputError(what + ": must be in " + describe_range(option) + ", got " +
                     with_unit(value, unit_of(option)));
  }
  return value;
}

std::uint64_t parse_whole_number(const std::string& text, const WholeOption& option, const std::string& what) {
  const std::string range = "[" + std::to_string(option.min) + ", " + std::to_string(option.max) + "]";
  std::uint64_t value = 0;
  const WholeNumberRead read = read_whole_number(text, &value);
  if (read == WholeNumberRead::too_large) throw InputError(what + ": must be in " + range + ", got " + text);
  if (read != WholeNumberRead::ok) {
    throw InputError(what + ": expected " + std::string(option.what) + " in " + range + ", got \"" + text + "\"");
  }
  if (value < option.min || value > option.max) {
    throw InputError(what + ": must be in " + range + ", got " + text);
  }
  return value;
}

}  // namespace hapscene
