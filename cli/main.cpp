// fogradar: automotive surround sensors in fog. Exit status 0 ok, 2 bad usage or bad input, 1
// internal fault, 130 / 143 `run` or `sweep` stopped by SIGINT / SIGTERM.
#include <CLI/CLI.hpp>
#include <chrono>
#include <exception>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "commands.hpp"
#include "fogradar/core/error.hpp"
#include "fogradar/sweep/mpi.hpp"

int main(int argc, char** argv) {
  constexpr int bad_input = 2;
  // Under mpirun or srun every rank parses the same command line: rank 0 alone says what is wrong.
  // The launcher ends the job at the first rank to exit with an error, so the others wait a moment
  // before they do, letting rank 0 finish saying it.
  const bool speaks = fogradar::sweep::launched_rank().value_or(0) == 0;
  std::ostringstream unsaid;
  std::ostream& err = speaks ? std::cerr : unsaid;
  const auto refuse = [speaks] {
    if (!speaks) std::this_thread::sleep_for(std::chrono::seconds(1));
    return bad_input;
  };
  CLI::App app{"fogradar: automotive surround sensors in fog, simulated from physics"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string(FOGRADAR_VERSION));
  const fogradar::cli::Action run = fogradar::cli::add_run_command(app);
  const fogradar::cli::Action scenario = fogradar::cli::add_scenario_command(app);
  const fogradar::cli::Action fog = fogradar::cli::add_fog_command(app);
  const fogradar::cli::Action sweep = fogradar::cli::add_sweep_command(app);
  const fogradar::cli::Action room = fogradar::cli::add_room_command(app);
  // CLI11 answers a word that is no subcommand with "A subcommand is required", not naming it.
  if (argc > 1 && argv[1][0] != '-') {
    const std::string word = argv[1];
    const std::vector<CLI::App*> known =
        app.get_subcommands([&word](CLI::App* sub) { return sub->check_name(word); });
    if (known.empty()) {
      err << "fogradar: unknown subcommand '" << word
          << "': must be one of run, scenario, fog, sweep, room\n"
          << "(run 'fogradar --help' for usage)\n";
      return refuse();
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const fogradar::InvalidParameter& e) {  // an option's check (cli/checks.hpp)
    err << "fogradar: " << e.what() << '\n';
    return refuse();
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    err << "fogradar: " << e.what() << "\n(run 'fogradar --help' for usage)\n";
    return refuse();
  }
  try {
    if (app.got_subcommand("run")) run();
    if (app.got_subcommand("scenario")) scenario();
    if (app.got_subcommand("fog")) fog();
    if (app.got_subcommand("sweep")) sweep();
    if (app.got_subcommand("room")) room();
  } catch (const fogradar::sweep::RefusedOnRankZero&) {
    return bad_input;
  } catch (const fogradar::cli::Interrupted& e) {
    err << "fogradar: " << e.what() << '\n';
    return 128 + e.signal_number();
  } catch (const fogradar::InvalidParameter& e) {
    err << "fogradar: " << e.what() << '\n';
    return refuse();
  } catch (const std::exception& e) {
    std::cerr << "fogradar: internal error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
