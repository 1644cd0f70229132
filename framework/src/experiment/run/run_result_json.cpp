#include "stochnav/experiment/run_result_json.hpp"

#include <cmath>
#include <limits>

#include "stochnav/core/errors.hpp"

namespace stochnav {
namespace {

constexpr const char* kNonFiniteKey = "non_finite";

nlohmann::json marked_double(double x) {
  if (std::isfinite(x)) return x;
  if (std::isnan(x)) return {{kNonFiniteKey, "nan"}};
  return {{kNonFiniteKey, x > 0.0 ? "inf" : "-inf"}};
}

bool is_non_finite_marker(const nlohmann::json& value) {
  return value.is_object() && value.size() == 1 && value.contains(kNonFiniteKey) &&
         value[kNonFiniteKey].is_string();
}

double restored_double(const nlohmann::json& value, const std::string& where) {
  if (value.is_number()) return value.get<double>();
  if (is_non_finite_marker(value)) {
    const auto& text = value[kNonFiniteKey].get_ref<const std::string&>();
    if (text == "nan") return std::numeric_limits<double>::quiet_NaN();
    if (text == "inf") return std::numeric_limits<double>::infinity();
    if (text == "-inf") return -std::numeric_limits<double>::infinity();
  }
  throw InputError(where + ": expected a number, found " + value.dump() +
                   "; the shard's job file is damaged: rerun the shard");
}

const nlohmann::json& member(const nlohmann::json& json, const char* key,
                             const std::string& where) {
  if (!json.is_object() || !json.contains(key)) {
    throw InputError(where + ": missing \"" + key +
                     "\"; the shard's job file is damaged or from another stochnav version: "
                     "rerun the shard");
  }
  return json[key];
}

template <std::size_t N>
nlohmann::json marked_array(const std::array<double, N>& values) {
  nlohmann::json out = nlohmann::json::array();
  for (double x : values) out.push_back(marked_double(x));
  return out;
}

template <std::size_t N>
std::array<double, N> restored_array(const nlohmann::json& json, const std::string& where) {
  if (!json.is_array() || json.size() != N) {
    throw InputError(where + ": expected an array of " + std::to_string(N) +
                     " numbers; the shard's job file is damaged: rerun the shard");
  }
  std::array<double, N> out{};
  for (std::size_t i = 0; i < N; ++i) out[i] = restored_double(json[i], where);
  return out;
}

}  // namespace

nlohmann::json with_non_finite_marked(const nlohmann::json& value) {
  if (value.is_number_float()) return marked_double(value.get<double>());
  if (value.is_array()) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& item : value) out.push_back(with_non_finite_marked(item));
    return out;
  }
  if (value.is_object()) {
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [key, item] : value.items()) out[key] = with_non_finite_marked(item);
    return out;
  }
  return value;
}

nlohmann::json with_non_finite_restored(const nlohmann::json& value) {
  if (is_non_finite_marker(value)) return restored_double(value, "");
  if (value.is_array()) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& item : value) out.push_back(with_non_finite_restored(item));
    return out;
  }
  if (value.is_object()) {
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [key, item] : value.items()) out[key] = with_non_finite_restored(item);
    return out;
  }
  return value;
}

nlohmann::json run_result_to_json(const NavigationRunResult& run, bool with_error_series) {
  std::array<double, kErrorMetricCount> max_abs{}, sum_squares{};
  std::array<std::size_t, kErrorMetricCount> count{};
  for (std::size_t m = 0; m < kErrorMetricCount; ++m) {
    max_abs[m] = run.statistics.max_abs(m);
    sum_squares[m] = run.statistics.sum_squares(m);
    count[m] = run.statistics.count(m);
  }
  nlohmann::json series = nlohmann::json::array();
  if (with_error_series) {
    for (const auto& sample : run.error_series) {
      series.push_back({{"t_s", marked_double(sample.t_s)},
                        {"errors", marked_array(sample.errors)},
                        {"sigma", marked_array(sample.sigma)}});
    }
  }
  return {{"has_truth", run.has_truth},
          {"statistics",
           {{"max_abs", marked_array(max_abs)},
            {"sum_squares", marked_array(sum_squares)},
            {"count", count}}},
          {"health",
           {{"singular_innovations", run.health.singular_innovations},
            {"repaired_diagonals", run.health.repaired_diagonals},
            {"non_finite", run.health.non_finite}}},
          {"epochs", run.epochs},
          {"duration_s", marked_double(run.duration_s)},
          {"wall_seconds", marked_double(run.wall_seconds)},
          {"error_series", series},
          {"noise_models", with_non_finite_marked(run.noise_models)},
          {"fitted", with_non_finite_marked(run.fitted)},
          {"fit_quality", with_non_finite_marked(run.fit_quality)},
          {"consistency", with_non_finite_marked(run.consistency)},
          {"aids", with_non_finite_marked(run.aids)},
          {"self_check", run.self_check},
          {"consistency_line", run.consistency_line},
          {"warnings", run.warnings},
          {"survey_stations", run.survey_stations}};
}

NavigationRunResult run_result_from_json(const nlohmann::json& json, const std::string& where) {
  NavigationRunResult run;
  try {
    run.has_truth = member(json, "has_truth", where).get<bool>();
    const auto& statistics = member(json, "statistics", where);
    run.statistics = ErrorStatistics::from_parts(
        restored_array<kErrorMetricCount>(member(statistics, "max_abs", where), where),
        restored_array<kErrorMetricCount>(member(statistics, "sum_squares", where), where),
        member(statistics, "count", where).get<std::array<std::size_t, kErrorMetricCount>>());
    const auto& health = member(json, "health", where);
    run.health.singular_innovations =
        member(health, "singular_innovations", where).get<std::uint64_t>();
    run.health.repaired_diagonals =
        member(health, "repaired_diagonals", where).get<std::uint64_t>();
    run.health.non_finite = member(health, "non_finite", where).get<std::uint64_t>();
    run.epochs = member(json, "epochs", where).get<std::uint64_t>();
    run.duration_s = restored_double(member(json, "duration_s", where), where);
    run.wall_seconds = restored_double(member(json, "wall_seconds", where), where);
    for (const auto& sample : member(json, "error_series", where)) {
      run.error_series.push_back(
          {restored_double(member(sample, "t_s", where), where),
           restored_array<kErrorMetricCount>(member(sample, "errors", where), where),
           restored_array<kErrorMetricCount>(member(sample, "sigma", where), where)});
    }
    run.noise_models = with_non_finite_restored(member(json, "noise_models", where));
    run.fitted = with_non_finite_restored(member(json, "fitted", where));
    run.fit_quality = with_non_finite_restored(member(json, "fit_quality", where));
    run.consistency = with_non_finite_restored(member(json, "consistency", where));
    run.aids = with_non_finite_restored(member(json, "aids", where));
    run.self_check = member(json, "self_check", where);
    run.consistency_line = member(json, "consistency_line", where).get<std::string>();
    run.warnings = member(json, "warnings", where).get<std::vector<std::string>>();
    run.survey_stations = member(json, "survey_stations", where).get<std::size_t>();
  } catch (const nlohmann::json::exception& error) {
    throw InputError(where + ": a member has the wrong type (" + error.what() +
                     "); the shard's job file is damaged: rerun the shard");
  }
  return run;
}

}  // namespace stochnav
