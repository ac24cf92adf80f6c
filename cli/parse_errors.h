// How the command line reports what CLI11 refuses: one line starting "pmrender: ", exit code 2
// (help and --version print as usual, exit code 0).
#pragma once

#include <CLI/CLI.hpp>

namespace pm::cli {

// Prints the message for a parse error of `app` (argv as given to main) and returns the exit code.
int report_parse_error(CLI::App& app, const CLI::ParseError& error, int argc, char** argv);

}  // namespace pm::cli
