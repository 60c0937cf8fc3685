#pragma once
// The entry point of every `freeplay` front, without CLI11: `main` needs only this (command_registry.hpp has the rest).

namespace freeplay::cli {

/// Parses the command line against every registered subcommand and runs it; returns the exit status (2 on bad
/// input, with the error on stderr).
int run_program(int argc, char** argv);

}  // namespace freeplay::cli
