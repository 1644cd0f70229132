#include "stochnav/report/gnuplot.hpp"

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "stochnav/core/errors.hpp"
#include "stochnav/io/atomic_file.hpp"

namespace stochnav {
namespace {

std::string quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\'') {
      out += "'\\''";
    } else {
      out += c;
    }
  }
  return out + "'";
}

}  // namespace

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
  PendingFile picture(output);
  PendingFile script_file(output.string() + ".gp");
  {
    std::ofstream out(script_file.temporary_path());
    out << terminal << "set output " << quoted(picture.temporary_path().string()) << "\n"
        << script << "\nunset output\n";
  }
  const std::string command = "gnuplot " + quoted(script_file.temporary_path().string()) + " 2>&1";
  std::FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) throw InputError("cannot start gnuplot");
  std::string messages;
  std::array<char, 512> chunk{};
  while (std::fgets(chunk.data(), chunk.size(), pipe) != nullptr) messages += chunk.data();
  const int status = ::pclose(pipe);
  if (status != 0 || !std::filesystem::exists(picture.temporary_path())) {
    const auto first_line = messages.substr(0, messages.find('\n', messages.find_first_not_of('\n')));
    throw InputError(output.string() + ": gnuplot failed: " + first_line);
  }
  picture.commit();
}

}  // namespace stochnav
