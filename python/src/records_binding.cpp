// stochnav.read_record: one channel of a record file (CSV, Stable32-style text, raw float64,
// gzip) read by the library's reader, with its checks and messages, into a numpy array.

#include <fmt/format.h>

#include <optional>

#include "arguments.hpp"
#include "bindings.hpp"
#include "json_values.hpp"
#include "numpy_arrays.hpp"
#include "stochnav/io/record.hpp"

namespace stochnav::python {
namespace {

struct RecordChannel {
  py::array_t<double> values;
  double rate_hz = 0.0;
  double start_time_s = 0.0;
  std::string data;
  std::string unit;
  std::string source;
  std::string column;
};

// A column by name or by 0-based index (an int or digits).
std::string column_argument(const py::handle& column) {
  if (column.is_none()) return "";
  if (py::isinstance<py::int_>(column)) return std::to_string(column.cast<long long>());
  return py::str(column).cast<std::string>();
}

RecordChannel read_channel(const py::object& path, const py::object& column,
                           std::optional<double> rate, const std::string& data,
                           const std::string& unit) {
  ReadOptions options;
  options.path = path_from_python(path).string();
  options.column = column_argument(column);
  if (rate) options.rate_hz = *rate;
  options.kind = data_kind_argument(data);
  options.unit = unit_argument(unit);
  Record record;
  {
    py::gil_scoped_release release;
    record = read_record(options);
  }
  RecordChannel channel;
  channel.rate_hz = record.rate_hz;
  channel.start_time_s = record.start_time_s;
  channel.data = data;
  channel.unit = unit_name(record.unit);
  channel.source = record.source;
  channel.column = record.column;
  channel.values = to_numpy(std::move(record.values));
  return channel;
}

constexpr const char* kReadRecordDoc = R"(One channel of a record file, as the CLI's --input, --column, --rate read it.

Parameters
----------
path : str or os.PathLike
    CSV with a header row (an optional time column t, t_s or time gives the rate), text with
    whitespace-separated numbers and # comments (Stable32 style), raw little-endian .f64/.f32,
    or any of them gzip-compressed (.gz).
column : str or int, optional
    Column name, or its 0-based index; default: the first that is not time.
rate : float, optional
    Sampling rate (Hz); needed when the file has no time column.
data : str
    "rate" or "phase" (recorded in the result; the values are returned as read).
unit : str
    "deg/h", "deg/s", "rad/s", "m/s^2", "g" or "plain" (recorded in the result).

Returns
-------
Record
    values (numpy float64, as in the file), rate_hz, start_time_s (s), data, unit, source,
    column.

Raises
------
InputError (a ValueError)
    Malformed content, naming the file and line (NaN, ragged rows, non-uniform time, ...).
ConfigError (a ValueError)
    No rate and no time column; a rate out of range.
)";

}  // namespace

void bind_records(py::module_& module) {
  py::class_<RecordChannel>(module, "Record",
                            "One channel of a record file (stochnav.read_record).")
      .def_readonly("values", &RecordChannel::values, "samples as in the file")
      .def_readonly("rate_hz", &RecordChannel::rate_hz, "sampling rate (Hz)")
      .def_readonly("start_time_s", &RecordChannel::start_time_s, "time of values[0] (s)")
      .def_readonly("data", &RecordChannel::data, "\"rate\" or \"phase\"")
      .def_readonly("unit", &RecordChannel::unit, "unit of the samples")
      .def_readonly("source", &RecordChannel::source, "the file")
      .def_readonly("column", &RecordChannel::column, "the column read")
      .def("__len__", [](const RecordChannel& r) { return r.values.size(); })
      .def("__repr__", [](const RecordChannel& r) {
        return fmt::format("<Record: {} [{}], {} {} samples at {:g} Hz, unit {}>", r.source,
                           r.column, r.values.size(), r.data, r.rate_hz, r.unit);
      });
  module.def("read_record", &read_channel, py::arg("path"), py::arg("column") = py::none(),
             py::arg("rate") = py::none(), py::arg("data") = "rate", py::arg("unit") = "plain",
             kReadRecordDoc);
}

}  // namespace stochnav::python
