#include "stochnav/fit/gmwm_data.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include "stochnav/core/errors.hpp"
#include "stochnav/io/line_reader.hpp"
#include "stochnav/io/text_cells.hpp"
#include "stochnav/stats/robust_wavelet_variance.hpp"

namespace stochnav {

std::string validate(const GmwmData& data) {
  const std::size_t n = data.scale_s.size();
  if (data.wv.size() != n || data.wv_lo.size() != n || data.wv_hi.size() != n) {
    return data.source + ": scale_s, wv, wv_lo and wv_hi differ in length";
  }
  if (n < 3) {
    return fmt::format(
        "{}: {} wavelet-variance scale(s); GMWM needs at least 3 (a record of 16 "
        "samples or more)",
        data.source, n);
  }
  if (!(data.rate_hz > 0.0) || !std::isfinite(data.rate_hz)) {
    return data.source + ": the sampling rate is not > 0; give --rate";
  }
  if (std::all_of(data.wv.begin(), data.wv.end(), [](double v) { return v == 0.0; })) {
    return data.source +
           ": the wavelet variance is zero at every scale (a constant record); "
           "check --column";
  }
  for (std::size_t j = 0; j < n; ++j) {
    const bool ok = std::isfinite(data.scale_s[j]) && data.scale_s[j] > 0.0 &&
                    (j == 0 || data.scale_s[j] > data.scale_s[j - 1]) &&
                    std::isfinite(data.wv_hi[j]) && data.wv[j] > 0.0 &&
                    data.wv_lo[j] <= data.wv[j] && data.wv_hi[j] > data.wv[j];
    if (!ok) {
      return fmt::format(
          "{}: scale {} (scale_s {:g}): need ascending scales > 0 and 0 < wv <= "
          "wv_hi with wv_lo <= wv (got wv {:g}, interval [{:g}, {:g}])",
          data.source, j + 1, data.scale_s[j], data.wv[j], data.wv_lo[j], data.wv_hi[j]);
    }
  }
  return {};
}

GmwmData gmwm_data_from_rate(std::span<const double> rate, double rate_hz, Unit unit, bool robust,
                             const std::string& source) {
  if (wavelet_variance_levels(rate.size()) < 3) {
    throw InputError(
        fmt::format("{}: {} samples give fewer than 3 wavelet-variance scales; "
                    "GMWM needs 16 samples or more",
                    source, rate.size()));
  }
  if (std::all_of(rate.begin(), rate.end(), [&](double y) { return y == rate.front(); })) {
    throw InputError(source +
                     ": the rate is constant (every sample the same); its wavelet "
                     "variance is zero; check --column");
  }
  const auto levels =
      robust ? robust_haar_wavelet_variance(rate, rate_hz) : haar_wavelet_variance(rate, rate_hz);
  return gmwm_data_from_levels(levels, unit, rate_hz, source);
}

GmwmData gmwm_data_from_levels(std::span<const WaveletVariancePoint> levels, Unit unit,
                               double rate_hz, std::string source) {
  GmwmData data;
  const double s2 = si_per_unit(unit) * si_per_unit(unit);
  for (const auto& level : levels) {
    data.scale_s.push_back(level.scale_s);
    data.wv.push_back(level.variance * s2);
    data.wv_lo.push_back(level.lower * s2);
    data.wv_hi.push_back(level.upper * s2);
  }
  data.unit = unit;
  data.rate_hz = rate_hz;
  data.source = std::move(source);
  return data;
}

namespace {

std::string_view unquoted(std::string_view cell) {
  cell = trim(cell);
  if (cell.size() >= 2 && cell.front() == '"' && cell.back() == '"') {
    cell = cell.substr(1, cell.size() - 2);
  }
  return cell;
}

/// The header index of the first of `names` present.
std::optional<std::size_t> column_index(const std::vector<std::string>& header,
                                        std::initializer_list<std::string_view> names) {
  for (std::string_view name : names) {
    const auto it = std::find(header.begin(), header.end(), name);
    if (it != header.end()) return static_cast<std::size_t>(it - header.begin());
  }
  return std::nullopt;
}

}  // namespace

GmwmData read_wavelet_variance_table(const std::string& path, const std::string& channel, Unit unit,
                                     double rate_hz) {
  LineReader lines(path);
  std::string_view line;
  std::vector<std::string_view> cells;
  std::vector<std::string> header;
  while (lines.next(line)) {
    if (trim(line).empty() || trim(line).front() == '#') continue;
    split_cells(line, ',', cells);
    for (auto cell : cells) header.emplace_back(unquoted(cell));
    break;
  }
  const auto scale = column_index(header, {"scale_s"});
  const auto wv = column_index(header, {"wv"});
  const auto lo = column_index(header, {"ci_low", "wv_lo"});
  const auto hi = column_index(header, {"ci_high", "wv_hi"});
  if (!scale || !wv || !lo || !hi) {
    throw InputError(fmt::format(
        "{}: the wavelet-variance table needs the columns scale_s, wv and ci_low, ci_high (or "
        "wv_lo, wv_hi); its header has {}",
        path, header.empty() ? std::string("nothing") : fmt::format("{}", fmt::join(header, ","))));
  }
  const auto channel_column = column_index(header, {"channel"});
  const auto freq_column = column_index(header, {"freq"});
  std::map<std::string, std::size_t> channels;  // rows per channel, to name them in errors
  GmwmData data;
  const std::size_t needed = std::max({*scale, *wv, *lo, *hi}) + 1;
  while (lines.next(line)) {
    if (trim(line).empty() || trim(line).front() == '#') continue;
    split_cells(line, ',', cells);
    if (cells.size() < needed) {
      throw InputError(fmt::format("{}:{}: {} cells, the header has {}", path, lines.line_number(),
                                   cells.size(), header.size()));
    }
    if (channel_column) {
      const std::string name(unquoted(cells[*channel_column]));
      ++channels[name];
      if (!channel.empty() && name != channel) continue;
    }
    double values[4];
    const std::size_t at[4] = {*scale, *wv, *lo, *hi};
    for (int k = 0; k < 4; ++k) {
      if (!parse_number(unquoted(cells[at[k]]), values[k]) || !std::isfinite(values[k])) {
        throw InputError(fmt::format("{}:{}: '{}' in column {} is not a finite number", path,
                                     lines.line_number(), cells[at[k]], header[at[k]]));
      }
    }
    if (freq_column && !(rate_hz > 0.0)) {
      double freq = 0.0;
      if (parse_number(unquoted(cells[*freq_column]), freq) && freq > 0.0) data.rate_hz = freq;
    }
    data.scale_s.push_back(values[0]);
    data.wv.push_back(values[1]);
    data.wv_lo.push_back(values[2]);
    data.wv_hi.push_back(values[3]);
  }
  std::string names;
  for (const auto& [name, rows] : channels) names += (names.empty() ? "'" : ", '") + name + "'";
  if (channel_column && channel.empty() && channels.size() > 1) {
    throw InputError(fmt::format("{}: the table holds {} channels ({}); choose one with --column",
                                 path, channels.size(), names));
  }
  if (!channel.empty() && channel_column && !channels.contains(channel)) {
    throw InputError(
        fmt::format("{}: no channel '{}' in the table; it has {}", path, channel, names));
  }
  if (rate_hz > 0.0) data.rate_hz = rate_hz;
  if (!(data.rate_hz > 0.0)) {
    throw InputError(path + ": the table has no freq column; give the record's rate with --rate");
  }
  const double s2 = si_per_unit(unit) * si_per_unit(unit);
  for (auto* column : {&data.wv, &data.wv_lo, &data.wv_hi}) {
    for (double& v : *column) v *= s2;
  }
  data.unit = unit;
  data.source = channel.empty() ? path : path + " [" + channel + "]";
  if (const auto problem = validate(data); !problem.empty()) throw InputError(problem);
  return data;
}

}  // namespace stochnav
