#pragma once
// `stochnav fit --method gmwm`: the Haar wavelet variance of the record (classical, or robust
// with --robust) or a table given by --wv-table, fitted by GMWM (fit/gmwm_fit.hpp), one model
// (--terms) or several ranked by WIC (--candidates).

#include "fit_arguments.hpp"

namespace stochnav::cli {

/// Writes the fit (json/table/csv) as the Allan-variance fit does. Throws InputError or
/// ConfigError (exit 2) for bad input, an option only an avar fit takes, or a failed fit
/// without --keep-failed.
void run_gmwm_fit(const FitArguments& arguments);

}  // namespace stochnav::cli
