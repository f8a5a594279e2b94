#pragma once
// Python values to engine settings: numbers in SI or strings with units ("10 mm"), range
// checked by the command line's own option definitions (engine/cli/option_definitions.hpp),
// so a value the CLI refuses is refused here too, with the same range in the message.
#include <pybind11/pybind11.h>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/base/axes.hpp"
#include "engine/cli/arguments.hpp"

namespace hapscene::python {

namespace py = pybind11;

// `value` (a float, an int or a str with a unit) as `option` reads it. `what` names it in
// messages ("hapscene.simulate: duration"). Throws InputError.
double quantity(const py::handle& value, const QuantityOption& option, const std::string& what);
std::optional<double> optional_quantity(const py::object& value, const QuantityOption& option, const std::string& what);

// A whole number (int, or str of digits) in the option's range.
std::uint64_t whole(const py::handle& value, const WholeOption& option, const std::string& what);

// A point (x, y): a sequence of two quantities, or "X,Y" as the command line writes it.
Vec2 point(const py::handle& value, const QuantityOption& option, const std::string& what);

// A list of names: a sequence of str, or one str of comma-separated names.
std::vector<std::string> names(const py::handle& value, const std::string& what);

// "/path/env.json" from a str or an os.PathLike.
std::string path_text(const py::handle& value, const std::string& what);

}  // namespace hapscene::python
