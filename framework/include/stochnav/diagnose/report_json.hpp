#pragma once
// DIR/report.json of `stochnav diagnose`, exactly the DESIGN.md contract:
//   {"consistent": bool, "gap_initial": x, "gap_final": y,
//    "iterations": [{"effect": TYPE, "evidence": "...", "tau_range_s": [a, b] | null,
//                    "time_range_s": [t0, t1] | null, "added_term": {...},
//                    "gap_before": x, "gap_after": y}],
//    "final_model": {...}}
// plus, when diagnose read the wavelet variance (DiagnoseOptions::try_wavelet), two keys beside
// the contract's (new keys only; the contract's are unchanged):
//   "wavelet_outliers": {"contaminated": bool, "explained_by_nonstationary": bool,
//     "scale_range_s": [a, b] | null,
//     "largest_excess": x, "largest_excess_scale_s": s | null, "wv_unit": "(deg/s)^2",
//     "levels": [{"scale_s", "edf", "classical", "classical_lo", "classical_hi", "robust",
//                 "robust_lo", "robust_hi", "excess", "tested", "flagged"}],
//     "z_threshold": z, "differences_beyond": n, "worst_samples": [{"time_s", "index", "z"}],
//     "summary": "..."}                        (diagnose/wavelet_outliers.hpp)
//   "short_tau_gauss_markov": {"applicable": bool, "named": bool, "effect": "gauss_markov" | null,
//     "added_term": {gauss_markov with "sigma_sigma", "tau_c_sigma"} | null,
//     "tau_c_on_range_end": "lower" | "upper" | null, "in_model": bool,
//     "robust_wv": bool, "scales": n, "objective_without": x, "objective_with": y,
//     "threshold": t, "largest_share": s,
//     "largest_share_scale_s": s, "lag1_model": r, "lag1_record": r,
//     "summary": "..."}                        (diagnose/short_tau_gauss_markov.hpp)
// Terms and the final model are in the reporting units of model/noise_model_json.hpp; ranges in
// seconds (time from the first sample of the record).

#include <nlohmann/json.hpp>

#include "stochnav/diagnose/diagnose.hpp"

namespace stochnav {

nlohmann::json diagnose_report_json(const DiagnoseResult& result);

}  // namespace stochnav
