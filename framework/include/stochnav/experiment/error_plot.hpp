#pragma once
// Plot of navigation errors over time: three panels (position, velocity, attitude), each error
// with its +/- 3-sigma bounds as dashed lines (gnuplot, report/gnuplot.hpp).

#include <filesystem>
#include <string>
#include <vector>

#include "stochnav/experiment/navigation_run.hpp"

namespace stochnav {

/// Renders `series` to `path` (.png or .svg). Throws ConfigError / InputError as render_gnuplot.
void plot_navigation_errors(const std::vector<ErrorSample>& series, const std::string& title,
                            const std::filesystem::path& path);

}  // namespace stochnav
