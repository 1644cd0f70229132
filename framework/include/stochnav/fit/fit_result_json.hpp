#pragma once
// JSON form of a fit (`stochnav fit --format json`): the noise-model JSON of DESIGN.md in
// reporting units, each parameter followed by its 1-sigma uncertainty, plus diagnostics.
//
//   {"units": "deg/h", "rate_hz": 100,
//    "terms": [{"type": "angle_random_walk", "N": 0.05, "N_sigma": 0.001}, ...],
//    "diagnostics": {
//      "cost": 4.1, "chi_square": 8.3, "points": 15, "parameters": 3,
//      "criterion": "bic", "criterion_value": 16.4, "loss": "huber", "loss_scale": 2,
//      "iterations": 7, "converged": true, "automatic": true,
//      "chosen_terms": ["quantization", "angle_random_walk", "rate_random_walk"],
//      "slope_readoffs": {"Q": {"value": 0.21, "unit": "arcsec", "tau_s": 0.01}, "N": {...},
//                         "B": {...}, "K": {...}, "R": {...}},
//      "selection": [{"terms": ["angle_random_walk"], "criterion": 130.2, "accepted": true}, ...],
//      "warnings": [], "failed": false, "failure": "", "dropped_terms": [], "at_bound": [],
//      "undetermined": []}}
//
// Every fit also carries "method": "avar" | "gmwm". A GMWM fit (fit/gmwm_fit.hpp) has criterion
// "wic", loss "none", and in "diagnostics" "objective" and "j_test": {"statistic", "dof",
// "p_value"}; a ranked one a top-level "ranking": [{"terms": [...], "wic": x, "objective": y}],
// best first.
//
// "failed" flags a failed fit (FitDiagnostics::failed: a parameter on its search bound, one
// without an uncertainty, or a chi-square the terms cannot explain) and "failure" says why;
// `stochnav fit` writes such a result only with --keep-failed, and `simulate noise` refuses a
// model flagged so unless given --accept-failed.
//
// An uncertainty that could not be determined is null. noise_model_from_json reads this document
// back as a plain noise model.

#include <nlohmann/json.hpp>

#include "stochnav/fit/fit_noise_terms.hpp"

namespace stochnav {

nlohmann::json fit_result_to_json(const FitResult& result);

}  // namespace stochnav
