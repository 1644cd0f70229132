#pragma once
// Runs the stochnav command-line tool from tests and captures its exit code and output.

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace stochnav::testing {

struct CliResult {
  int exit_code = -1;
  std::string out;  ///< standard output
  std::string err;  ///< standard error
};

/// Runs `stochnav <arguments>` (arguments already shell-quoted as needed).
inline CliResult run_cli(const std::string& arguments, const std::string& scratch_dir) {
  const std::string err_path = scratch_dir + "/stderr.txt";
  const std::string command =
      std::string("'") + STOCHNAV_CLI_PATH + "' " + arguments + " 2> '" + err_path + "'";
  CliResult result;
  std::FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> chunk{};
  while (std::fgets(chunk.data(), chunk.size(), pipe) != nullptr) result.out += chunk.data();
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (std::FILE* err = std::fopen(err_path.c_str(), "r")) {
    while (std::fgets(chunk.data(), chunk.size(), err) != nullptr) result.err += chunk.data();
    std::fclose(err);
  }
  std::remove(err_path.c_str());
  return result;
}

}  // namespace stochnav::testing
