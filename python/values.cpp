#include "python/values.hpp"

#include <string>

#include "engine/base/errors.hpp"
#include "engine/base/format.hpp"

namespace hapscene::python {

double quantity(const py::handle& value, const QuantityOption& option, const std::string& what) {
  // Numbers go through their shortest exact text, which reads back as the same double.
  std::string text;
  if (py::isinstance<py::bool_>(value)) throw InputError(what + ": expected a number or a string with a unit, got a bool");
  if (py::isinstance<py::str>(value)) {
    text = value.cast<std::string>();
  } else if (py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value) ||
             py::hasattr(value, "__float__")) {
    text = py::repr(py::float_(py::reinterpret_borrow<py::object>(value))).cast<std::string>();
  } else {
    throw InputError(what + ": expected a number or a string with a unit, got " +
                     py::str(py::type::handle_of(value).attr("__name__")).cast<std::string>());
  }
  return parse_option_quantity(text, option, what);
}

std::optional<double> optional_quantity(const py::object& value, const QuantityOption& option, const std::string& what) {
  if (value.is_none()) return std::nullopt;
  return quantity(value, option, what);
}

std::uint64_t whole(const py::handle& value, const WholeOption& option, const std::string& what) {
  if (py::isinstance<py::bool_>(value) || !(py::isinstance<py::int_>(value) || py::isinstance<py::str>(value))) {
    throw InputError(what + ": expected " + std::string(option.what));
  }
  return parse_whole_number(py::str(value).cast<std::string>(), option, what);
}

Vec2 point(const py::handle& value, const QuantityOption& option, const std::string& what) {
  if (py::isinstance<py::str>(value)) {
    const std::string text = value.cast<std::string>();
    const std::size_t comma = text.find(',');
    if (comma == std::string::npos || text.find(',', comma + 1) != std::string::npos) {
      throw InputError(what + ": a 2-DOF environment takes X,Y, got \"" + text + "\"");
    }
    return Vec2{{parse_option_quantity(text.substr(0, comma), option, what + " X"),
                 parse_option_quantity(text.substr(comma + 1), option, what + " Y")}};
  }
  if (!py::isinstance<py::sequence>(value) || py::len(value) != 2) {
    throw InputError(what + ": a 2-DOF environment takes a point (x, y)");
  }
  const py::sequence pair = py::reinterpret_borrow<py::sequence>(value);
  return Vec2{{quantity(pair[0], option, what + " X"), quantity(pair[1], option, what + " Y")}};
}

std::vector<std::string> names(const py::handle& value, const std::string& what) {
  std::vector<std::string> out;
  if (py::isinstance<py::str>(value)) {
    return split_names(value.cast<std::string>());
  }
  if (!py::isinstance<py::sequence>(value)) throw InputError(what + ": expected a list of names or a str");
  for (const py::handle item : value) {
    if (!py::isinstance<py::str>(item)) throw InputError(what + ": expected names (str)");
    out.push_back(item.cast<std::string>());
  }
  return out;
}

std::string path_text(const py::handle& value, const std::string& what) {
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::hasattr(value, "__fspath__")) {
    const py::object path = value.attr("__fspath__")();
    if (py::isinstance<py::str>(path)) return path.cast<std::string>();
  }
  throw InputError(what + ": expected a path (str or os.PathLike) or a hapscene.Scene");
}

}  // namespace hapscene::python
