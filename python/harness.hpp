#pragma once
#include <pybind11/pybind11.h>

namespace hapscene::python {

// hapscene.validate and hapscene.test (harness.cpp).
void bind_harness(pybind11::module_& m);

}  // namespace hapscene::python
