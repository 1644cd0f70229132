#pragma once
// Error types of stochnav. The CLI maps InputError and ConfigError to exit code 2 and prints
// their message as one line; anything else is an internal failure (exit code 1).

#include <stdexcept>
#include <string>

namespace stochnav {

/// Bad input data: the message names the file and line, what is wrong and how to fix it.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
  ~InputError() override;
};

/// Bad configuration (JSON or command-line options): the message names the JSON pointer or the
/// option, the value found and the expected form.
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
  ~ConfigError() override;
};

/// A configuration that is valid but names data that are not there (a column of the aid data,
/// a simulated scenario's folder). Tools that check a config before its data exist (compare
/// validates every variant before simulating) catch this one and nothing else.
class MissingDataError : public ConfigError {
 public:
  using ConfigError::ConfigError;
  ~MissingDataError() override;
};

}  // namespace stochnav
