// Names and per-estimator constants of the Allan-family deviations.

#include <array>
#include <string>

#include "stochnav/core/errors.hpp"
#include "stochnav/stats/deviation.hpp"

namespace stochnav {
namespace {

constexpr std::array<Deviation, 7> kAllDeviations = {
    Deviation::kAdev, Deviation::kOadev, Deviation::kMdev,  Deviation::kTdev,
    Deviation::kHdev, Deviation::kOhdev, Deviation::kTotdev};

}  // namespace

std::string_view deviation_name(Deviation kind) {
  switch (kind) {
    case Deviation::kAdev:
      return "adev";
    case Deviation::kOadev:
      return "oadev";
    case Deviation::kMdev:
      return "mdev";
    case Deviation::kTdev:
      return "tdev";
    case Deviation::kHdev:
      return "hdev";
    case Deviation::kOhdev:
      return "ohdev";
    case Deviation::kTotdev:
      return "totdev";
  }
  return "unknown";
}

std::optional<Deviation> deviation_from_name(std::string_view name) {
  for (Deviation kind : kAllDeviations) {
    if (deviation_name(kind) == name) return kind;
  }
  return std::nullopt;
}

Deviation parse_deviation(std::string_view name) {
  if (const auto kind = deviation_from_name(name)) return *kind;
  throw ConfigError("deviation '" + std::string(name) +
                    "' is unknown: use adev, oadev, mdev, tdev, hdev, ohdev or totdev");
}

int difference_order(Deviation kind) {
  return kind == Deviation::kHdev || kind == Deviation::kOhdev ? 3 : 2;
}

bool is_overlapping(Deviation kind) { return kind != Deviation::kAdev && kind != Deviation::kHdev; }

bool is_modified(Deviation kind) { return kind == Deviation::kMdev || kind == Deviation::kTdev; }

std::size_t term_count(Deviation kind, std::size_t m, std::size_t phase_count) {
  if (m == 0 || phase_count == 0) return 0;
  const std::size_t n = phase_count;
  const auto positive = [](std::size_t a, std::size_t b) { return a > b ? a - b : 0; };
  switch (kind) {
    case Deviation::kAdev:
      return positive((n - 1) / m, 1);
    case Deviation::kOadev:
      return positive(n, 2 * m);
    case Deviation::kMdev:
    case Deviation::kTdev:
      return positive(n + 1, 3 * m);
    case Deviation::kHdev:
      return positive((n - 1) / m, 2);
    case Deviation::kOhdev:
      return positive(n, 3 * m);
    case Deviation::kTotdev:
      return n >= 3 && m <= n - 2 ? n - 2 : 0;
  }
  return 0;
}

std::size_t max_averaging_factor(Deviation kind, std::size_t phase_count) {
  if (phase_count < 3) return 0;
  if (kind == Deviation::kTotdev) return (phase_count - 2) / 2;
  const std::size_t divisor = is_overlapping(kind) ? 4 : 5;
  return (phase_count - 2) / divisor;
}

}  // namespace stochnav
