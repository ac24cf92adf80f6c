// One-line messages for command-line parse errors. CLI11's own report is two lines ("... Run with
// --help for more information.") and says "A subcommand is required" for a misspelt command.
#include "cli/parse_errors.h"

#include <cstdio>
#include <string>

namespace pm::cli {

namespace {

std::string command_list(const CLI::App& app) {
  std::string list;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; }))
    list += (list.empty() ? "" : ", ") + sub->get_name();
  return list;
}

std::string one_line(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

}  // namespace

int report_parse_error(CLI::App& app, const CLI::ParseError& error, int argc, char** argv) {
  if (error.get_exit_code() == 0) return app.exit(error);  // --help, --version
  std::string message = one_line(error.what());
  // No subcommand was recognised: name what was given instead of "A subcommand is required".
  if (app.get_subcommands().empty()) {
    const std::string commands = " (commands: " + command_list(app) + ")";
    if (argc < 2) {
      message = "no command given" + commands;
    } else {
      const std::string first = argv[1];
      message = (!first.empty() && first[0] == '-' ? "unknown option '" : "unknown command '") + one_line(first) +
                "'" + commands;
    }
  }
  std::fprintf(stderr, "pmrender: %s\n", message.c_str());
  return 2;
}

}  // namespace pm::cli
