// pena: PeNa's offline tool. Subcommands are in cmd_*.cpp; errors end as one line on stderr.
#include <cstdlib>
#include <exception>
#include <iostream>

#include <CLI/CLI.hpp>

#include "commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"pena: personal localisation and mapping tools (PeNa)"};
  app.require_subcommand(1);
  pena::cli::AddSimulateCommand(app);
  pena::cli::AddInfoCommand(app);
  pena::cli::AddEvalCommand(app);
  pena::cli::AddExportCommand(app);
  pena::cli::AddOdometryCommand(app);
  pena::cli::AddMapCommand(app);
  pena::cli::AddLocaliseCommand(app);
  pena::cli::AddReportCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error);
  } catch (const std::exception& error) {
    // Readers already say "file:line: what"; keep it on one line so scripts can grep it.
    std::cerr << "pena: error: " << error.what() << '\n';
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
