// Reading a run's innovations.csv (experiment/run/run_files.cpp writes it):
//   t,aid,type,accepted,nis,z0..z5,sigma0..sigma5   (unused components empty; nis may be nan)

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <map>
#include <string_view>

#include "stochnav/core/errors.hpp"
#include "stochnav/diagnose/innovation_analysis.hpp"
#include "stochnav/io/line_reader.hpp"
#include "stochnav/io/text_cells.hpp"

namespace stochnav {
namespace {

constexpr std::size_t kMaxComponents = 6;
constexpr std::size_t kColumns = 5 + 2 * kMaxComponents;

std::string expected_header() {
  std::string header = "t,aid,type,accepted,nis";
  for (const char* prefix : {"z", "sigma"}) {
    for (std::size_t i = 0; i < kMaxComponents; ++i) header += fmt::format(",{}{}", prefix, i);
  }
  return header;
}

}  // namespace

std::vector<AidInnovations> read_innovations(const std::string& path) {
  LineReader lines(path);
  std::string_view line;
  if (!lines.next(line) || trim(line) != expected_header()) {
    throw InputError(
        fmt::format("{}:1: not an innovations file of `stochnav run` (expected the "
                    "header {}); pass the folder written by `stochnav run --out`",
                    path, expected_header()));
  }
  std::map<int, AidInnovations> by_aid;
  std::vector<std::string_view> cells;
  while (lines.next(line)) {
    if (trim(line).empty()) continue;
    const auto where = [&] { return fmt::format("{}:{}", path, lines.line_number()); };
    split_cells(line, ',', cells);
    if (cells.size() != kColumns) {
      throw InputError(
          fmt::format("{}: {} cells, expected {}; the file is truncated or "
                      "edited, rerun `stochnav run`",
                      where(), cells.size(), kColumns));
    }
    std::array<double, 4> head{};  // t, aid, accepted, nis
    const std::array<std::size_t, 4> head_columns{0, 1, 3, 4};
    for (std::size_t k = 0; k < head.size(); ++k) {
      if (!parse_number(cells[head_columns[k]], head[k]) || (k < 3 && !std::isfinite(head[k]))) {
        throw InputError(fmt::format("{}: column {}: '{}' is not a number; rerun `stochnav run`",
                                     where(), head_columns[k] + 1, cells[head_columns[k]]));
      }
    }
    InnovationSample sample{.t_s = head[0], .accepted = head[2] != 0.0, .nis = head[3]};
    for (std::size_t i = 0; i < kMaxComponents; ++i) {
      const std::string_view z_cell = trim(cells[5 + i]);
      if (z_cell.empty()) break;
      double z = 0.0, sigma = 0.0;
      if (!parse_number(z_cell, z) || !parse_number(cells[5 + kMaxComponents + i], sigma)) {
        throw InputError(
            fmt::format("{}: component {}: not a number; rerun `stochnav run`", where(), i));
      }
      sample.z.push_back(z);
      sample.sigma.push_back(sigma);
    }
    const int aid_index = static_cast<int>(head[1]);
    AidInnovations& aid = by_aid[aid_index];
    if (aid.samples.empty()) {
      aid.aid_index = aid_index;
      aid.type = std::string(trim(cells[2]));
    } else if (sample.t_s < aid.samples.back().t_s) {
      throw InputError(
          fmt::format("{}: time {} before the previous update of aid {}; rerun "
                      "`stochnav run`",
                      where(), sample.t_s, aid_index));
    }
    aid.samples.push_back(std::move(sample));
  }
  if (by_aid.empty()) {
    throw InputError(path +
                     ": no aid updates; the run had no aids (add one to the run config) "
                     "or no measurements");
  }
  std::vector<AidInnovations> aids;
  for (auto& [index, aid] : by_aid) aids.push_back(std::move(aid));
  return aids;
}

}  // namespace stochnav
