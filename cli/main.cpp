// fogradar: automotive surround sensors in fog. Exit status 0 ok, 2 bad usage or bad input, 1
// internal fault, 130 / 143 `run` or `sweep` stopped by SIGINT / SIGTERM.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "fogradar/core/error.hpp"

int main(int argc, char** argv) {
  constexpr int bad_input = 2;
  CLI::App app{"fogradar: automotive surround sensors in fog, simulated from physics"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string(FOGRADAR_VERSION));
  const fogradar::cli::Action run = fogradar::cli::add_run_command(app);
  const fogradar::cli::Action scenario = fogradar::cli::add_scenario_command(app);
  const fogradar::cli::Action fog = fogradar::cli::add_fog_command(app);
  const fogradar::cli::Action sweep = fogradar::cli::add_sweep_command(app);
  // CLI11 answers a word that is no subcommand with "A subcommand is required", not naming it.
  if (argc > 1 && argv[1][0] != '-') {
    const std::string word = argv[1];
    const std::vector<CLI::App*> known =
        app.get_subcommands([&word](CLI::App* sub) { return sub->check_name(word); });
    if (known.empty()) {
      std::cerr << "fogradar: unknown subcommand '" << word
                << "': must be one of run, scenario, fog, sweep\n"
                << "(run 'fogradar --help' for usage)\n";
      return bad_input;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const fogradar::InvalidParameter& e) {  // an option's check (cli/checks.hpp)
    std::cerr << "fogradar: " << e.what() << '\n';
    return bad_input;
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "fogradar: " << e.what() << "\n(run 'fogradar --help' for usage)\n";
    return bad_input;
  }
  try {
    if (app.got_subcommand("run")) run();
    if (app.got_subcommand("scenario")) scenario();
    if (app.got_subcommand("fog")) fog();
    if (app.got_subcommand("sweep")) sweep();
  } catch (const fogradar::cli::Interrupted& e) {
    std::cerr << "fogradar: " << e.what() << '\n';
    return 128 + e.signal_number();
  } catch (const fogradar::InvalidParameter& e) {
    std::cerr << "fogradar: " << e.what() << '\n';
    return bad_input;
  } catch (const std::exception& e) {
    std::cerr << "fogradar: internal error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
