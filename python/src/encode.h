#pragma once

#include <pybind11/pybind11.h>

namespace dbss::python {

// encode(points, options, with_stats) and encode_file(path, out_path, options).
void register_encode(pybind11::module_& m);

}  // namespace dbss::python
