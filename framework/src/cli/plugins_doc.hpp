#pragma once
// `stochnav plugins doc`, a subcommand of `plugins` (plugins_command.cpp).

#include <CLI/CLI.hpp>

namespace stochnav::cli {

void add_plugins_doc_command(CLI::App& plugins_command);

}  // namespace stochnav::cli
