// The `freeplay` program's command line, shared by both executables (cli/main.cpp, cli/light_main.cpp).

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <iostream>

#include "command_registry.hpp"
#include "sibling_program.hpp"
#include "freeplay/core/assets.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/core/memory.hpp"

namespace freeplay::cli {

std::vector<CommandEntry>& registered_commands() {
  static std::vector<CommandEntry> entries;
  return entries;
}

std::vector<ListerEntry>& registered_listers() {
  static std::vector<ListerEntry> entries;
  return entries;
}

namespace {

char** g_arguments = nullptr;

void add_list_command(CLI::App& program) {
  auto* list = program.add_subcommand("list", "List what this installation provides (items, scenarios, …)");
  list->require_subcommand(1);
  auto& listers = registered_listers();
  std::sort(listers.begin(), listers.end(), [](const auto& a, const auto& b) { return a.what < b.what; });
  for (const auto& entry : listers) {
    auto* sub = list->add_subcommand(entry.what, entry.description);
    auto json = std::make_shared<bool>(false);
    sub->add_flag("--json", *json, "Print JSON instead of a table");
    sub->callback([&entry, json] { entry.print(*json); });
  }
}

}  // namespace
}  // namespace freeplay::cli

namespace freeplay::cli {

char** program_arguments() { return g_arguments; }

int run_program(int argc, char** argv) {
  g_arguments = argv;
  keep_freed_memory_for_reuse();  // episodes, one after another on each worker, reuse each other's pages
  // Logs go to stderr so that stdout carries only results (tables, JSON) that programs can parse.
  spdlog::set_default_logger(spdlog::stderr_color_mt("freeplay"));
  CLI::App program{"freeplay — simulate, benchmark and record Free-play Sandbox sessions (sandtray, Nao, children)",
                   "freeplay"};
  program.set_version_flag("--version", std::string("freeplay ") + freeplay::program_version());
  program.require_subcommand(1);
  program.fallthrough();
  bool verbose = false;
  bool quiet = false;
  program.add_flag("-v,--verbose", verbose, "Log debug messages to stderr");
  program.add_flag("-q,--quiet", quiet, "Log only errors to stderr");
  program.parse_complete_callback([&] {
    spdlog::set_level(verbose ? spdlog::level::debug : quiet ? spdlog::level::err : spdlog::level::info);
  });

  auto& commands = registered_commands();
  std::stable_sort(commands.begin(), commands.end(), [](const auto& a, const auto& b) { return a.order < b.order; });
  for (const auto& command : commands) command.setup(program);
  if (!registered_listers().empty()) add_list_command(program);

  try {
    program.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = program.exit(e);
    // CLI11 uses 106–110 for usage errors; bad arguments are bad input: exit status 2 like other tools.
    return (code == 0 || e.get_name() == "RuntimeError") ? code : 2;
  } catch (const freeplay::InputError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

}  // namespace freeplay::cli
