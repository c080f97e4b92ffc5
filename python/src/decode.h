#pragma once

#include <pybind11/pybind11.h>

namespace dbss::python {

// decode(data, level), the streaming Decoder and info(data, name, hashes).
void register_decode(pybind11::module_& m);

}  // namespace dbss::python
