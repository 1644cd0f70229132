#pragma once
// DIR/report.json of `stochnav diagnose`, exactly the DESIGN.md contract:
//   {"consistent": bool, "gap_initial": x, "gap_final": y,
//    "iterations": [{"effect": TYPE, "evidence": "...", "tau_range_s": [a, b] | null,
//                    "time_range_s": [t0, t1] | null, "added_term": {...},
//                    "gap_before": x, "gap_after": y}],
//    "final_model": {...}}
// Terms and the final model are in the reporting units of model/noise_model_json.hpp; ranges in
// seconds (time from the first sample of the record).

#include <nlohmann/json.hpp>

#include "stochnav/diagnose/diagnose.hpp"

namespace stochnav {

nlohmann::json diagnose_report_json(const DiagnoseResult& result);

}  // namespace stochnav
