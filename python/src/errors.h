// dbss Status errors crossing into Python: thrown as StatusError in C++,
// raised as the dbss.Error subclass of their code (python/dbss/_errors.py)
// with the code, its name and the byte offset.
#pragma once

#include <exception>

#include <pybind11/pybind11.h>

#include "dbss/format/status.h"

namespace dbss::python {

struct StatusError : std::exception {
  explicit StatusError(Status s) : status(std::move(s)) {}
  const char* what() const noexcept override { return status.message().c_str(); }
  Status status;
};

// Raises `status` (not ok) as a Python exception.
[[noreturn]] inline void throw_status(const Status& status) { throw StatusError(status); }

void register_errors(pybind11::module_& m);

}  // namespace dbss::python
