#pragma once
// `freeplay serve SCENARIO --web [ADDR:]PORT`: the served episode watched and driven from the experimenter's web page
// (freeplay_web, docs/web.md), without a ROS master.

#include <CLI/CLI.hpp>
#include <atomic>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace freeplay::cli {

/// The `--web…` options of `freeplay serve`.
struct WebCliOptions {
  std::string listen;              ///< `[ADDR:]PORT`; empty: no web page
  std::string token;               ///< access token (required beyond loopback)
  std::string out;                 ///< session folder (default runs/web-<UTC time>)
  std::string mode = "autonomous"; ///< robot mode at the start
  double sparc_timeout_s = 2.0;    ///< SPARC proposal timeout
  bool no_linger = false;          ///< exit when the episode ends instead of waiting for `finalise`
  bool record = false;             ///< the session's bag records from the start
  bool ros = false;                ///< also take `sparc/selected_action` from a ROS master
  bool graph = false;              ///< also serve the game's topics, services and signals on a ROS master
  double master_timeout_s = 10.0;  ///< how long to wait for it
};

/// Adds the `--web…` options to the `serve` subcommand.
void add_web_options(CLI::App& serve, WebCliOptions& options);

/// Runs the web session of `serve` (exit status 130 when interrupted during the episode).
void run_web_serve(const std::string& file, const std::vector<std::string>& overrides, std::optional<std::uint64_t> seed,
                   double rate, const WebCliOptions& options, const std::atomic<bool>& stop);

}  // namespace freeplay::cli
