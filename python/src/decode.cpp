// dbss.decode, dbss.Decoder and dbss.info over the C++ ProgressiveDecoder
// and the report of `dbss info` (tools/info_report.h).
#include "decode.h"

#include <mutex>
#include <optional>
#include <utility>
#include <span>
#include <string>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "arrays.h"
#include "dbss/decoder/progressive.h"
#include "errors.h"
#include "info_report.h"

namespace dbss::python {

namespace py = pybind11;

namespace {

// The bytes of any contiguous buffer (bytes, bytearray, memoryview, a uint8
// array).  The buffer_info keeps the exporter alive while the GIL is released.
struct Bytes {
  explicit Bytes(const py::buffer& b) : info(b.request()) {
    if (info.ndim > 1 || info.itemsize != 1 || (info.ndim == 1 && info.strides[0] != 1))
      throw py::type_error("expected bytes (a contiguous buffer of single bytes)");
  }
  std::span<const uint8_t> span() const {
    return {static_cast<const uint8_t*>(info.ptr), static_cast<size_t>(info.size)};
  }
  py::buffer_info info;
};

// Decoded levels reach Python as (vertices float32 V x 3, faces uint32 F x 3)
// owning vectors copied once from the decoder's view (which the next
// decode() overwrites), without the GIL; rows_of_3 hands them over uncopied.

// What `dbss decode` says when `level` cannot be had from `d`, or ok.  A
// level outside the file is invalid_argument (dbss.InvalidArgumentError, a
// ValueError too).
Status check_level(const ProgressiveDecoder& d, long level, const Status& end) {
  const int ready = d.ready_level();
  if (ready < 0) return end.ok() ? Status(ErrorCode::truncated, "no control mesh yet") : end;
  const long declared = d.reader().header().level_count;
  if (level < 0 || level > declared)
    return Status(ErrorCode::invalid_argument,
                  "level " + std::to_string(level) + " is not in the file (levels 0.." + std::to_string(declared) + ")");
  if (level > ready) {
    const std::string why = "level " + std::to_string(level) + " is not available (finest verified level: " +
                            std::to_string(ready) + ")";
    if (end.ok()) return Status(ErrorCode::truncated, why + ": its bytes have not arrived");
    return Status(end.code(), why + ": " + end.message(), end.offset());
  }
  return Status();
}

// The streaming decoder: bytes in as they arrive, any ready level out.  Calls
// release the GIL, so each object has a lock, only ever taken without the GIL
// (no thread can hold one while waiting for the other).
class Decoder {
  template <class F>
  auto locked(F&& f) -> decltype(f()) {
    py::gil_scoped_release nogil;
    std::lock_guard lock(mutex_);
    return f();
  }

 public:
  int push(const py::buffer& b) {
    Bytes bytes(b);
    const auto [s, ready] = locked([&] {
      Status fed = d_.feed(bytes.span());  // before ready_level(): arguments have no order
      return std::pair(std::move(fed), d_.ready_level());
    });
    if (!s.ok()) throw_status(s);
    return ready;
  }
  void finish() {
    const Status s = locked([&] { return d_.finish(); });
    if (!s.ok()) throw_status(s);
  }
  int levels_ready() { return locked([&] { return d_.ready_level(); }); }
  py::object levels() {
    const int n = locked([&] { return d_.reader().has_header() ? int{d_.reader().header().level_count} : -1; });
    return n < 0 ? py::object(py::none()) : py::object(py::int_(n));
  }
  py::object error() {
    const Status s = locked([&] { return d_.status(); });
    if (s.ok()) return py::none();
    const py::object offset = s.offset() == Status::kNoOffset ? py::object(py::none()) : py::int_(s.offset());
    return py::module_::import("dbss._errors")
        .attr("from_status")(static_cast<int>(s.code()), error_code_name(s.code()), offset, s.message());
  }
  py::tuple level(long l) {
    TriangleMesh mesh;
    const Status s = locked([&] {
      Status st = check_level(d_, l, d_.status());
      if (!st.ok()) return st;
      auto view = d_.decode(static_cast<uint32_t>(l));
      if (!view.ok()) return view.status();
      mesh = view.value().copy();  // the view is overwritten by the next decode
      return Status();
    });
    if (!s.ok()) throw_status(s);
    return py::make_tuple(rows_of_3(std::move(mesh.positions)), rows_of_3(std::move(mesh.triangles)));
  }

 private:
  std::mutex mutex_;
  ProgressiveDecoder d_;
};

}  // namespace

void register_decode(py::module_& m) {
  m.def(
      "decode",
      [](const py::buffer& data, std::optional<long> level) {
        Bytes bytes(data);
        ProgressiveDecoder d;
        Status end;
        {
          py::gil_scoped_release nogil;
          d.feed(bytes.span());
          end = d.finish();
        }
        const long want = level ? *level : d.ready_level();
        if (Status s = check_level(d, want, end); !s.ok()) throw_status(s);
        if (!level && !end.ok())
          py::module_::import("warnings")
              .attr("warn")("dbss.decode: " + end.to_string() + "; returning level " + std::to_string(want) +
                                ", the finest verified before it",
                            py::module_::import("dbss._errors").attr("PartialFileWarning"), 2);
        TriangleMesh mesh;
        Status decoded;
        {
          py::gil_scoped_release nogil;
          auto view = d.decode(static_cast<uint32_t>(want));
          if (view.ok()) mesh = view.value().copy();  // the decoder dies here; its view with it
          else decoded = view.status();
        }
        if (!decoded.ok()) throw_status(decoded);
        return py::make_tuple(rows_of_3(std::move(mesh.positions)), rows_of_3(std::move(mesh.triangles)));
      },
      py::arg("data"), py::arg("level") = py::none());

  py::class_<Decoder>(m, "Decoder")
      .def(py::init<>())
      .def("push", &Decoder::push, py::arg("data"))
      .def("finish", &Decoder::finish)
      .def_property_readonly("levels_ready", &Decoder::levels_ready)
      .def_property_readonly("levels", &Decoder::levels)
      .def_property_readonly("error", &Decoder::error)
      .def("level", &Decoder::level, py::arg("level"));

  m.def(
      "info",
      [](const py::buffer& data, std::optional<std::string> name, bool hashes) {
        Bytes bytes(data);
        std::string json;
        {
          py::gil_scoped_release nogil;
          json = tools::info_json(tools::inspect_bytes(bytes.span(), hashes), name);
        }
        return py::module_::import("json").attr("loads")(json);
      },
      py::arg("data"), py::arg("name") = py::none(), py::arg("hashes") = false);
}

}  // namespace dbss::python
