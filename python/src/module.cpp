// dbss._dbss: the C++ codec for Python.  The package dbss (python/dbss)
// checks arguments and documents the API; this wraps the libraries.
#include <pybind11/pybind11.h>

#include "decode.h"
#include "encode.h"
#include "errors.h"

PYBIND11_MODULE(_dbss, m) {
  m.doc() = "dbss codec (C++); use the dbss package";
  m.attr("__version__") = DBSS_VERSION;
  dbss::python::register_errors(m);
  dbss::python::register_encode(m);
  dbss::python::register_decode(m);
}
