#pragma once
// The plots of `stochnav diagnose`: measured vs model Allan deviation with the simulated band,
// before and after each step, and the DAVAR of the record when an effect is nonstationary.

#include <filesystem>
#include <string>

#include "stochnav/diagnose/diagnose.hpp"
#include "stochnav/io/record.hpp"

namespace stochnav::cli {

/// Measured OADEV (dense, with the octave 68.3 % intervals), `after` (closed form and simulated
/// band) and, when given, `before` (closed form, dashed). Title names the record and `label`.
void plot_diagnose_step(const MeasuredStatistics& measured, const ModelAssessment* before,
                        const ModelAssessment& after, const std::string& label,
                        const Record& record, const std::filesystem::path& output);

/// The record's DAVAR at its first octave taus over the stationarity windows' length (step half
/// a window), with the windows' short-tau level expected under `model` (the quiet level times
/// its nonstationary scale^2) over it.
void plot_diagnose_davar(const Record& record, const MeasuredStatistics& measured,
                         const StationarityTest& test, const NoiseModel& model,
                         const std::filesystem::path& output);

}  // namespace stochnav::cli
