#pragma once
#include <pybind11/pybind11.h>

namespace hapscene::python {

// hapscene.simulate (simulate.cpp).
void bind_simulate(pybind11::module_& m);

}  // namespace hapscene::python
