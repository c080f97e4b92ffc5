// numpy arrays over C++ vectors without copying: the vector moves into a
// capsule the array keeps alive.
#pragma once

#include <cstdint>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

namespace dbss::python {

template <class T>
pybind11::array_t<T> rows_of_3(std::vector<T>&& v) {
  auto* owned = new std::vector<T>(std::move(v));
  pybind11::capsule free_it(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  const pybind11::ssize_t rows = static_cast<pybind11::ssize_t>(owned->size() / 3);
  return pybind11::array_t<T>({rows, pybind11::ssize_t{3}}, owned->data(), free_it);
}

}  // namespace dbss::python
