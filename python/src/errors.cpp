#include "errors.h"

namespace dbss::python {

namespace py = pybind11;

void register_errors(py::module_& m) {
  // The exception classes live in Python (one per code, so callers can catch
  // e.g. dbss.ChecksumMismatchError); this only builds the instance.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const StatusError& e) {
      const Status& s = e.status;
      py::object offset = s.offset() == Status::kNoOffset ? py::object(py::none()) : py::object(py::int_(s.offset()));
      py::object exc = py::module_::import("dbss._errors")
                           .attr("from_status")(static_cast<int>(s.code()), error_code_name(s.code()), offset,
                                                s.message());
      PyErr_SetObject(reinterpret_cast<PyObject*>(Py_TYPE(exc.ptr())), exc.ptr());
    }
  });
  m.def("error_codes", [] {
    py::dict codes;
    for (int c = 0; c <= static_cast<int>(ErrorCode::internal); ++c)
      codes[py::str(error_code_name(static_cast<ErrorCode>(c)))] = c;
    return codes;
  }, "Every ErrorCode name with its pinned number.");
}

}  // namespace dbss::python
