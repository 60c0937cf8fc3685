#pragma once
// The commands a web client sends (`POST /api/command`, JSON): parsed and validated on the server thread before
// anything reaches the simulation, so that a malformed or out-of-range command gets a 4xx and never the robot.
// Schema: docs/web.md.

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace freeplay::web {

/// A refused request: the HTTP status (4xx) and a message naming the key and the allowed values.
class CommandError : public std::runtime_error {
 public:
  /// `status` is the HTTP status to answer; `message` says what is wrong and what is allowed.
  CommandError(int status, const std::string& message) : std::runtime_error(message), status_(status) {}
  /// HTTP status (400 malformed or out of range, 409 not possible now, 413 too large, …).
  int status() const { return status_; }

 private:
  int status_;
};

/// Where a validated command goes.
enum class CommandTarget { Robot, Protocol, Experiment, View, Component };

/// A validated command: its type and its normalised arguments (every field present and in range).
struct Command {
  std::string type;        ///< e.g. "move", "say", "mode", "signal", "demographics"
  nlohmann::json args;     ///< normalised arguments (object)
  CommandTarget target = CommandTarget::Robot;  ///< who handles it
};

/// Parses and validates one command body against the game's item names; throws CommandError (400) naming the
/// offending key and the allowed values.
Command parse_command(const std::string& body, const std::vector<std::string>& item_names);

/// The command types, comma-separated (for error messages and docs).
std::string command_types();

}  // namespace freeplay::web
