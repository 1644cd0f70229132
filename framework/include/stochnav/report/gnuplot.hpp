#pragma once
// Plots through gnuplot (an external program, Debian package gnuplot-nox).
//
// Scripts carry their data inline as datablocks, so a plot is one script and one output file;
// the picture is rendered to a temporary file and renamed into place when gnuplot succeeds.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace stochnav {

class PendingFile;

/// Checks a requested plot before any work is done: the file name ends in .png or .svg and
/// gnuplot is on PATH. Throws ConfigError (with an install hint when gnuplot is missing).
void check_plot_request(const std::filesystem::path& output);

/// `text` as a gnuplot single-quoted string, quotes included (inside one only '' is special):
/// for text a user chose (file names, columns, titles) in a script.
std::string gnuplot_string(std::string_view text);

/// A gnuplot datablock `$name << EOD ... EOD` with one row per index and one column per vector
/// (all columns the same length).
std::string gnuplot_datablock(const std::string& name,
                              const std::vector<const std::vector<double>*>& columns);

/// Renders `script` (without a `set terminal` / `set output` line) to `output`: the terminal is
/// chosen from the extension (.png: pngcairo 1000x700; .svg: svg). Throws ConfigError for other
/// extensions and InputError if gnuplot fails (with its first error line).
void render_gnuplot(const std::string& script, const std::filesystem::path& output);

/// The same into `picture`'s temporary file (the terminal from its final path; committing is
/// the caller's), for outputs committed together. gnuplot runs as a CleanupChild: a fatal
/// signal kills it before the temporary files are removed.
void render_gnuplot(const std::string& script, PendingFile& picture);

}  // namespace stochnav
