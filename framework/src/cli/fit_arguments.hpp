#pragma once
// The options of `stochnav fit`, shared by its Allan-variance path (fit_command.cpp) and its
// GMWM path (gmwm_fit_run.cpp).

#include <string>

#include "command_support.hpp"

namespace stochnav::cli {

struct FitArguments {
  InputArguments input;
  std::string method = "avar";  ///< avar | gmwm
  std::string terms;
  std::string taus = "octave";
  std::string loss = "huber";
  std::string criterion = "bic";
  std::size_t window = 0;
  std::size_t step = 0;
  std::string format = "table";
  std::string output;
  bool terms_given = false;  ///< --terms was on the command line (even empty)
  bool keep_failed = false;
  // GMWM only.
  bool robust = false;        ///< fit the robust wavelet variance
  std::string wv_table;       ///< a precomputed wavelet-variance table instead of --input
  std::string candidates;     ///< "a+b;a+b+c": rank by WIC
  std::string gauss_markov_sampling = "mean";  ///< mean | point (implied_wavelet_variance.hpp)
  // Parameter steering (fit/parameter_control_names.hpp), both methods.
  std::string start;
  std::string fix;
  std::string bound;
};

}  // namespace stochnav::cli
