#include "engine/cli/arguments.hpp"

#include <charconv>
#include <cmath>

#include "engine/base/errors.hpp"
#include "engine/base/object_reader.hpp"
#include "engine/base/whole_number.hpp"

namespace hapscene {
namespace {

// Where --name is given ("--name value" or "--name=value"), from `from` on; args.size() when not.
std::size_t find_option(const std::vector<std::string>& args, const std::string& option, std::size_t from) {
  for (std::size_t i = from; i < args.size(); ++i) {
    if (args[i] == option || args[i].starts_with(option + "=")) return i;
  }
  return args.size();
}

std::string unit_of(const QuantityOption& option) {
  return std::string(option.unit.empty() ? si_unit(option.quantity) : option.unit);
}

std::string with_unit(double value, const std::string& unit) {
  return format_number(value) + (unit.empty() ? "" : " " + unit);
}

}  // namespace

Arguments::Arguments(std::vector<std::string> args, std::string command)
    : args_(std::move(args)), command_(std::move(command)) {}

void Arguments::fail(const std::string& message) const {
  throw InputError(command_ + ": " + message);
}

std::optional<std::string> Arguments::take_value(std::string_view name) {
  const std::string option = "--" + std::string(name);
  const std::size_t i = find_option(args_, option, 0);
  if (i == args_.size()) return std::nullopt;
  std::string value;
  std::size_t used = 1;
  if (args_[i] == option) {
    if (i + 1 >= args_.size()) fail(option + " needs a value");
    value = args_[i + 1];
    // "--log --quiet" forgot the file name; it would otherwise write a file called "--quiet".
    if (value.starts_with("--") && value.size() > 2) fail(option + " needs a value, got the option " + value);
    used = 2;
  } else {
    value = args_[i].substr(option.size() + 1);
  }
  // A second --name (after this one's value) would otherwise be left over as "unknown".
  if (find_option(args_, option, i + used) != args_.size()) fail(option + " is given twice");
  args_.erase(args_.begin() + static_cast<std::ptrdiff_t>(i),
              args_.begin() + static_cast<std::ptrdiff_t>(i + used));
  return value;
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
  const std::string option = "--" + std::string(name);
  const std::size_t i = find_option(args_, option, 0);
  if (i == args_.size()) return false;
  if (args_[i] != option) fail(option + " takes no value, got \"" + args_[i] + "\"");
  if (find_option(args_, option, i + 1) != args_.size()) fail(option + " is given twice");
  args_.erase(args_.begin() + static_cast<std::ptrdiff_t>(i));
  return true;
}

std::vector<std::string> Arguments::positionals() const {
  for (const std::string& arg : args_) {
    if (arg.starts_with("--") && arg.size() > 2) fail("unknown option " + arg);
  }
  return args_;
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
