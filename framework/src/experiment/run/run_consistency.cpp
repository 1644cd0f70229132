#include "stochnav/experiment/run_consistency.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "stochnav/io/json_numbers.hpp"

namespace stochnav {
namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}  // namespace

double AidStatistics::nis_mean() const {
  const std::uint64_t accepted = attempts - rejected;
  return accepted > 0 ? nis_sum / static_cast<double>(accepted) : kNaN;
}

RunConsistency::RunConsistency(const std::vector<std::string>& aid_types,
                               const std::vector<int>& aid_dofs) {
  for (std::size_t i = 0; i < aid_types.size(); ++i) {
    aids_.push_back({.type = aid_types[i], .dof = i < aid_dofs.size() ? aid_dofs[i] : 0});
  }
}

void RunConsistency::add_epoch(const std::array<double, kErrorMetricCount>& errors,
                               const std::array<double, kErrorMetricCount>& sigma, double nees) {
  for (std::size_t i = 0; i < kErrorMetricCount; ++i) {
    if (!std::isfinite(errors[i]) || !std::isfinite(sigma[i])) continue;
    ++scored_[i];
    if (std::abs(errors[i]) <= 3.0 * sigma[i]) ++inside_[i];
  }
  if (std::isfinite(nees)) {
    nees_sum_ += nees;
    ++nees_count_;
  }
}

void RunConsistency::add_innovations(std::span<const InnovationRecord> records) {
  for (const InnovationRecord& record : records) {
    const auto index = static_cast<std::size_t>(record.aid_index);
    if (index >= aids_.size()) continue;
    AidStatistics& aid = aids_[index];
    ++aid.attempts;
    for (int i = 0; i < record.size && i < InnovationRecord::kMaxSize; ++i) {
      const double z = record.innovation[i];
      const double sigma = record.innovation_sigma[i];
      if (!std::isfinite(z) || !std::isfinite(sigma) || !(sigma > 0.0)) continue;
      ++aid.components;
      if (std::abs(z) <= 3.0 * sigma) ++aid.components_inside;
    }
    if (record.accepted && std::isfinite(record.nis)) {
      aid.nis_sum += record.nis;
    } else {
      ++aid.rejected;
    }
  }
}

std::uint64_t RunConsistency::accepted_updates() const {
  std::uint64_t accepted = 0;
  for (const AidStatistics& aid : aids_) accepted += aid.attempts - aid.rejected;
  return accepted;
}

double AidStatistics::inside_3sigma() const {
  return components > 0 ? static_cast<double>(components_inside) / static_cast<double>(components)
                        : kNaN;
}

double RunConsistency::inside_3sigma(std::size_t metric) const {
  return scored_[metric] > 0
             ? static_cast<double>(inside_[metric]) / static_cast<double>(scored_[metric])
             : kNaN;
}

double RunConsistency::nees_mean() const {
  return nees_count_ > 0 ? nees_sum_ / static_cast<double>(nees_count_) : kNaN;
}

nlohmann::json RunConsistency::consistency_json() const {
  if (!has_truth()) return nullptr;
  nlohmann::json inside = nlohmann::json::object();
  for (std::size_t i = 0; i < kErrorMetricCount; ++i) {
    inside[std::string(kErrorMetricNames[i])] = number_or_null(inside_3sigma(i));
  }
  return {{"inside_3sigma", inside},
          {"nees_mean", number_or_null(nees_mean())},
          {"nees_dof", 9},
          {"nees_samples", nees_count_}};
}

nlohmann::json RunConsistency::aids_json() const {
  nlohmann::json out = nlohmann::json::array();
  for (const AidStatistics& aid : aids_) {
    out.push_back({{"type", aid.type},
                   {"dof", aid.dof},
                   {"attempts", aid.attempts},
                   {"rejected_share", aid.rejected_share()},
                   {"nis_mean", number_or_null(aid.nis_mean())},
                   {"inside_3sigma", number_or_null(aid.inside_3sigma())}});
  }
  return out;
}

std::size_t RunConsistency::worst_metric() const {
  std::size_t worst = kErrorMetricCount;
  for (std::size_t i = 0; i < kErrorMetricCount; ++i) {
    const double share = inside_3sigma(i);
    if (!std::isfinite(share) || share >= kConsistentShare) continue;
    if (worst == kErrorMetricCount || share < inside_3sigma(worst)) worst = i;
  }
  return worst;
}

std::size_t RunConsistency::worst_aid() const {
  std::size_t worst = aids_.size();
  for (std::size_t i = 0; i < aids_.size(); ++i) {
    const double share = aids_[i].inside_3sigma();
    if (!std::isfinite(share) || share >= kConsistentShare) continue;
    if (worst == aids_.size() || share < aids_[worst].inside_3sigma()) worst = i;
  }
  return worst;
}

nlohmann::json RunConsistency::self_check_json() const {
  if (has_truth()) {
    const std::size_t worst = worst_metric();
    const bool optimistic = worst != kErrorMetricCount;
    return {
        {"source", "truth"},
        {"optimistic", optimistic},
        {"reason", optimistic ? fmt::format("{} inside 3-sigma only {:.0f} % of epochs",
                                            kErrorMetricNames[worst], 100.0 * inside_3sigma(worst))
                              : std::string()}};
  }
  const bool any_update = std::any_of(aids_.begin(), aids_.end(),
                                      [](const AidStatistics& aid) { return aid.components > 0; });
  if (!any_update) return {{"source", "none"}, {"optimistic", false}, {"reason", ""}};
  const std::size_t worst = worst_aid();
  const bool optimistic = worst != aids_.size();
  return {
      {"source", "innovations"},
      {"optimistic", optimistic},
      {"reason", optimistic ? fmt::format("{} innovations inside 3-sigma only {:.0f} % of {} "
                                          "components",
                                          aids_[worst].type, 100.0 * aids_[worst].inside_3sigma(),
                                          aids_[worst].components)
                            : std::string()}};
}

std::string RunConsistency::consistency_line() const {
  const nlohmann::json check = self_check_json();
  const std::string source = check["source"];
  const bool optimistic = check["optimistic"];
  if (source == "none") return {};
  if (source == "truth") {
    if (!optimistic)
      return fmt::format("consistency: ok (NEES mean {:.3g}, 9 expected)", nees_mean());
    return fmt::format("consistency: OPTIMISTIC ({})", check["reason"].get<std::string>());
  }
  if (optimistic) {
    return fmt::format("consistency (innovations, no truth): OPTIMISTIC ({})",
                       check["reason"].get<std::string>());
  }
  std::string shares;
  for (const AidStatistics& aid : aids_) {
    if (aid.components == 0) continue;
    shares += fmt::format("{}{} {:.1f} %", shares.empty() ? "" : ", ", aid.type,
                          100.0 * aid.inside_3sigma());
  }
  return fmt::format("consistency (innovations, no truth): ok (inside 3-sigma: {})", shares);
}

std::vector<std::string> RunConsistency::aid_warnings() const {
  std::vector<std::string> warnings;
  for (std::size_t i = 0; i < aids_.size(); ++i) {
    const AidStatistics& aid = aids_[i];
    if (aid.attempts == aid.rejected) {
      warnings.push_back(fmt::format(
          "warning: aid {} ({}) had no update accepted ({} attempts): the run navigated "
          "without it; check its data column and its times against the IMU record",
          i, aid.type, aid.attempts));
      continue;
    }
    if (aid.rejected_share() > kRejectionWarningShare) {
      warnings.push_back(fmt::format(
          "warning: aid {} ({}) rejected in {:.0f} % of {} updates (mean NIS {:.3g}, {} "
          "expected): the aid or the noise model does not match the data",
          i, aid.type, 100.0 * aid.rejected_share(), aid.attempts, aid.nis_mean(), aid.dof));
    }
  }
  return warnings;
}

}  // namespace stochnav
