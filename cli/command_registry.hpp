#pragma once
// Self-registration of `freeplay` subcommands: each cli/*.cpp adds its own, so no file lists them all.

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

#include "program.hpp"

namespace freeplay::cli {

/// Adds one subcommand (with its options and callback) to the program.
using CommandSetup = std::function<void(CLI::App& program)>;

/// A registered subcommand; `order` sorts the help listing.
struct CommandEntry {
  int order;           ///< position in `freeplay --help`
  CommandSetup setup;  ///< adds the subcommand
};

/// A `freeplay list <what>` provider.
struct ListerEntry {
  std::string what;                       ///< e.g. "items"
  std::string description;                ///< one line for --help
  std::function<void(bool json)> print;   ///< prints the list (as a table, or JSON when asked)
};

/// Every registered subcommand.
std::vector<CommandEntry>& registered_commands();
/// Every registered `list` provider.
std::vector<ListerEntry>& registered_listers();

/// Static registration helper: `static RegisterCommand reg(30, [](CLI::App& app) { ... });`.
struct RegisterCommand {
  /// Registers `setup` at position `order`.
  RegisterCommand(int order, CommandSetup setup) { registered_commands().push_back({order, std::move(setup)}); }
};

/// Static registration helper for `freeplay list <what>`.
struct RegisterLister {
  /// Registers a lister.
  RegisterLister(std::string what, std::string description, std::function<void(bool)> print) {
    registered_listers().push_back({std::move(what), std::move(description), std::move(print)});
  }
};

/// Exit status for a failure that is not bad input (e.g. no path found): makes CLI11 exit with `code`.
[[noreturn]] inline void fail_with(int code) { throw CLI::RuntimeError(code); }

}  // namespace freeplay::cli
