#include "stochnav/io/psins_imu.hpp"

#include <cmath>
#include <numbers>

#include "stochnav/core/errors.hpp"
#include "stochnav/io/line_reader.hpp"
#include "stochnav/io/text_cells.hpp"

namespace stochnav {
namespace {

constexpr double kArcsec = std::numbers::pi / (180.0 * 3600.0);
// ug*s per count -> m/s, with PSINS' own g0 (glv.g0 of the toolbox), not standard gravity.
constexpr double kMicroG = 9.7803267714e-6;

std::array<double, 6> six_numbers(LineReader& lines, std::string_view line,
                                  std::vector<std::string_view>& cells) {
  split_cells(line, ' ', cells);
  std::array<double, 6> values{};
  if (cells.size() != 6) {
    throw InputError(lines.path() + ":" + std::to_string(lines.line_number()) + ": " +
                     std::to_string(cells.size()) +
                     " numbers; a PSINS .imu row has 6 (check the file is PSINS SIMU text)");
  }
  for (std::size_t i = 0; i < 6; ++i) {
    if (!parse_number(cells[i], values[i]) || !std::isfinite(values[i])) {
      throw InputError(lines.path() + ":" + std::to_string(lines.line_number()) + ": '" +
                       echoed_text(trim(cells[i])) + "' is not a number; fix the row");
    }
  }
  return values;
}

}  // namespace

PsinsImuRecord read_psins_imu(const std::string& path) {
  LineReader lines(path);
  PsinsImuRecord record;
  std::vector<std::string_view> cells;
  std::string_view line;
  int header_rows = 0;
  std::array<double, 6> scale{};
  while (lines.next(line)) {
    line = trim(line);
    if (line.empty() || line.front() == '%') continue;
    const auto values = six_numbers(lines, line, cells);
    switch (header_rows++) {
      case 0:
        record.attitude_deg = {values[0], values[1], values[2]};
        record.velocity_mps = {values[3], values[4], values[5]};
        break;
      case 1:
        record.latitude_deg = values[0];
        record.longitude_deg = values[1];
        record.height_m = values[2];
        record.start_time_s = values[3];
        record.interval_s = values[4] * 1e-3;
        record.gravity_mps2 = values[5];
        break;
      case 2:
        scale = values;
        break;
      default: {
        std::array<double, 6> increment{};
        for (std::size_t i = 0; i < 6; ++i) {
          increment[i] = values[i] * scale[i] * (i < 3 ? kArcsec : kMicroG);
        }
        record.increments.push_back(increment);
      }
    }
  }
  if (header_rows < 3 || !(record.interval_s > 0.0)) {
    throw InputError(path + ": the three PSINS header rows (attitude, position and interval, "
                            "scales) are missing or the interval is not positive");
  }
  return record;
}

}  // namespace stochnav
