// The physics kernels for Python (lightcone.physics): each takes rows of float64 arrays (the
// package broadcasts them to one length first) and calls the library's scalar kernel on each
// row, so that it gives the C++ kernel's numbers, bit for bit.
#pragma once

#include <pybind11/pybind11.h>

namespace lightcone {

void add_physics_kernels(pybind11::module_ m);

}  // namespace lightcone
