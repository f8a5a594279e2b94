#include "engine/cli/arguments.hpp"

#include "engine/core/errors.hpp"

namespace hapscene {

Arguments::Arguments(std::vector<std::string> args, std::string command)
    : args_(std::move(args)), command_(std::move(command)) {}

void Arguments::fail(const std::string& message) const {
  throw InputError(command_ + ": " + message);
}

std::optional<std::string> Arguments::take_value(std::string_view name) {
  const std::string option = "--" + std::string(name);
  for (std::size_t i = 0; i < args_.size(); ++i) {
    if (args_[i] == option) {
      if (i + 1 >= args_.size()) fail(option + " needs a value");
      std::string value = args_[i + 1];
      args_.erase(args_.begin() + static_cast<std::ptrdiff_t>(i),
                  args_.begin() + static_cast<std::ptrdiff_t>(i + 2));
      return value;
    }
    if (args_[i].starts_with(option + "=")) {
      std::string value = args_[i].substr(option.size() + 1);
      args_.erase(args_.begin() + static_cast<std::ptrdiff_t>(i));
      return value;
    }
  }
  return std::nullopt;
}

std::optional<double> Arguments::take_quantity(std::string_view name, Quantity quantity) {
  const std::optional<std::string> text = take_value(name);
  if (!text) return std::nullopt;
  return parse_option_quantity(*text, quantity, command_ + ": --" + std::string(name));
}

bool Arguments::take_flag(std::string_view name) {
  const std::string option = "--" + std::string(name);
  for (std::size_t i = 0; i < args_.size(); ++i) {
    if (args_[i] == option) {
      args_.erase(args_.begin() + static_cast<std::ptrdiff_t>(i));
      return true;
    }
  }
  return false;
}

std::vector<std::string> Arguments::positionals() const {
  for (const std::string& arg : args_) {
    if (arg.starts_with("--") && arg.size() > 2) fail("unknown option " + arg);
  }
  return args_;
}

double parse_option_quantity(const std::string& text, Quantity quantity, const std::string& what) {
  const QuantityParse parsed = parse_quantity_as(text, quantity);
  if (!parsed.ok) throw InputError(what + ": " + parsed.error);
  return parsed.value_si;
}

}  // namespace hapscene
