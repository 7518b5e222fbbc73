// Subcommands of the `fogradar` tool. Each registers its options on the parent app and returns the
// action run after a successful parse. Bad input throws fogradar::InvalidParameter; main() maps it
// to exit status 2.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>

namespace fogradar::cli {

using Action = std::function<void()>;

Action add_fog_command(CLI::App& app);
Action add_run_command(CLI::App& app);
Action add_scenario_command(CLI::App& app);

}  // namespace fogradar::cli
