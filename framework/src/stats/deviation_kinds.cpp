// Names and per-estimator constants of the Allan-family deviations.

#include <array>
#include <string>

#include "stochnav/core/errors.hpp"
#include "stochnav/stats/deviation.hpp"

namespace stochnav {
namespace {

constexpr std::array<Deviation, 15> kAllDeviations = {
    Deviation::kAdev,        Deviation::kOadev,   Deviation::kMdev,          Deviation::kTdev,
    Deviation::kHdev,        Deviation::kOhdev,   Deviation::kTotdev,        Deviation::kMtotdev,
    Deviation::kTtotdev,     Deviation::kHtotdev, Deviation::kHtotdevNobias, Deviation::kTheo1,
    Deviation::kTheo1Nobias, Deviation::kMtie,    Deviation::kTierms};

/// Smallest Theo1 averaging factor (Stable32 and SP 1065: 10 <= m, m even).
constexpr std::size_t kTheo1MinFactor = 10;

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
    case Deviation::kMtotdev:
      return "mtotdev";
    case Deviation::kTtotdev:
      return "ttotdev";
    case Deviation::kHtotdev:
      return "htotdev";
    case Deviation::kHtotdevNobias:
      return "htotdev_nobias";
    case Deviation::kTheo1:
      return "theo1";
    case Deviation::kTheo1Nobias:
      return "theo1_nobias";
    case Deviation::kMtie:
      return "mtie";
    case Deviation::kTierms:
      return "tierms";
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
                    "' is unknown: use adev, oadev, mdev, tdev, hdev, ohdev, totdev, mtotdev, "
                    "ttotdev, htotdev, htotdev_nobias, theo1, theo1_nobias, mtie or tierms");
}

EdfRule parse_edf_rule(std::string_view name) {
  if (name == "plausible") return EdfRule::kPlausibleMinimum;
  if (name == "stable32") return EdfRule::kStable32;
  throw ConfigError("edf '" + std::string(name) + "' is unknown: use plausible or stable32");
}

int difference_order(Deviation kind) {
  switch (kind) {
    case Deviation::kHdev:
    case Deviation::kOhdev:
    case Deviation::kHtotdev:
    case Deviation::kHtotdevNobias:
      return 3;
    default:
      return 2;
  }
}

bool is_overlapping(Deviation kind) { return kind != Deviation::kAdev && kind != Deviation::kHdev; }

bool is_modified(Deviation kind) { return kind == Deviation::kMdev || kind == Deviation::kTdev; }

bool is_theo1(Deviation kind) {
  return kind == Deviation::kTheo1 || kind == Deviation::kTheo1Nobias;
}

bool has_confidence_interval(Deviation kind) {
  return kind != Deviation::kMtie && kind != Deviation::kTierms;
}

double tau_of(Deviation kind, std::size_t m, double tau0_s) {
  const double tau = static_cast<double>(m) * tau0_s;
  return is_theo1(kind) ? 0.75 * tau : tau;
}

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
    case Deviation::kMtotdev:
    case Deviation::kTtotdev:
      return positive(n + 1, 3 * m);
    case Deviation::kHtotdev:
    case Deviation::kHtotdevNobias:
      return positive(n, 3 * m);
    case Deviation::kTheo1:
    case Deviation::kTheo1Nobias:
      return m % 2 == 0 && m >= kTheo1MinFactor ? positive(n, m) * (m / 2) : 0;
    case Deviation::kMtie:
    case Deviation::kTierms:
      return positive(n, m);
  }
  return 0;
}

std::size_t max_averaging_factor(Deviation kind, std::size_t phase_count) {
  if (phase_count < 3) return 0;
  switch (kind) {
    case Deviation::kTotdev:
      return (phase_count - 2) / 2;
    case Deviation::kMtotdev:
    case Deviation::kTtotdev:
    case Deviation::kHtotdev:
    case Deviation::kHtotdevNobias:
      return (phase_count - 1) / 3;
    case Deviation::kTheo1:
    case Deviation::kTheo1Nobias:
      return phase_count >= kTheo1MinFactor + 3 ? phase_count - 3 : 0;
    case Deviation::kMtie:
      return phase_count - 1;
    default:
      break;
  }
  const std::size_t divisor = is_overlapping(kind) ? 4 : 5;
  return (phase_count - 2) / divisor;
}

}  // namespace stochnav
