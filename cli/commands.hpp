// Subcommands of the `fogradar` tool. Each registers its options on the parent app and returns the
// action run after a successful parse. Bad input throws fogradar::InvalidParameter; main() maps it
// to exit status 2.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <stdexcept>
#include <string>

namespace fogradar::cli {

using Action = std::function<void()>;

// Thrown by an action that SIGINT or SIGTERM stopped; main() exits with 128 + the signal number
// (130, 143), printing what() as the one message.
class Interrupted : public std::runtime_error {
 public:
  Interrupted(int signal_number, const std::string& message)
      : std::runtime_error(message), signal_number_(signal_number) {}
  int signal_number() const noexcept { return signal_number_; }

 private:
  int signal_number_;
};

Action add_fog_command(CLI::App& app);
Action add_room_command(CLI::App& app);
Action add_run_command(CLI::App& app);
Action add_scenario_command(CLI::App& app);
Action add_sweep_command(CLI::App& app);

}  // namespace fogradar::cli
