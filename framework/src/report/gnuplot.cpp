#include "stochnav/report/gnuplot.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdlib>
#include <sstream>

#include "stochnav/core/errors.hpp"
#include "stochnav/core/temporary_files.hpp"
#include "stochnav/io/atomic_file.hpp"

namespace stochnav {
namespace {

}  // namespace

std::string gnuplot_string(std::string_view text) {
  std::string out = "'";
  for (char c : text) {
    out += c;
    if (c == '\'') out += '\'';
  }
  return out + "'";
}

void check_plot_request(const std::filesystem::path& output) {
  const std::string extension = output.extension().string();
  if (extension != ".png" && extension != ".svg") {
    throw ConfigError("--plot " + output.string() + ": use a .png or .svg file name");
  }
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) {
    throw ConfigError(
        "--plot needs gnuplot, which is not on PATH; install it (apt-get install gnuplot-nox) "
        "or drop --plot");
  }
}

std::string gnuplot_datablock(const std::string& name,
                              const std::vector<const std::vector<double>*>& columns) {
  std::ostringstream out;
  out.precision(10);
  out << '$' << name << " << EOD\n";
  const std::size_t rows = columns.empty() ? 0 : columns.front()->size();
  for (std::size_t i = 0; i < rows; ++i) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      out << (c == 0 ? "" : " ") << (*columns[c])[i];
    }
    out << '\n';
  }
  out << "EOD\n";
  return out.str();
}

void render_gnuplot(const std::string& script, const std::filesystem::path& output) {
  PendingFile picture(output);
  render_gnuplot(script, picture);
  picture.commit();
}

void render_gnuplot(const std::string& script, PendingFile& picture) {
  const std::filesystem::path& output = picture.final_path();
  const std::string extension = output.extension().string();
  std::string terminal;
  if (extension == ".png") {
    terminal = "set terminal pngcairo size 1000,700 enhanced font 'Sans,10'\n";
  } else if (extension == ".svg") {
    terminal = "set terminal svg size 1000,700 enhanced font 'Sans,10'\n";
  } else {
    throw ConfigError("--plot " + output.string() + ": use a .png or .svg file name");
  }
  check_plot_request(output);
  PendingFile script_file(output.string() + ".gp");
  write_pending_file(script_file, terminal + "set output " +
                                      gnuplot_string(picture.temporary_path().string()) + "\n" + script +
                                      "\nunset output\n");
  CleanupChild gnuplot({"gnuplot", script_file.temporary_path().string()});
  std::string messages;
  std::array<char, 512> chunk{};
  for (;;) {
    const ssize_t count = ::read(gnuplot.output_fd(), chunk.data(), chunk.size());
    if (count > 0) {
      messages.append(chunk.data(), static_cast<std::size_t>(count));
    } else if (count == 0 || errno != EINTR) {
      break;
    }
  }
  const int status = gnuplot.wait();
  std::error_code size_error;
  // A picture written in place (a FIFO) has no size to check.
  const auto size = picture.in_place()
                        ? std::uintmax_t{1}
                        : std::filesystem::file_size(picture.temporary_path(), size_error);
  const bool drawn = WIFEXITED(status) && WEXITSTATUS(status) == 0 && !size_error && size > 0;
  if (!drawn) {
    const auto first_line = messages.substr(0, messages.find('\n', messages.find_first_not_of('\n')));
    throw InputError(output.string() + ": gnuplot failed: " + first_line);
  }
}

}  // namespace stochnav
