#pragma once
// Errors for bad input (scenario files, CLI arguments, policy actions, touches): they name where and what.

#include <stdexcept>
#include <string>

namespace freeplay {

/// Where in a source file a bad value stands (line and column are 1-based; 0 = unknown).
struct SourceLocation {
  std::string file;  ///< path as the user gave it; empty for values that come from code or the CLI
  int line = 0;      ///< 1-based line, 0 if unknown
  int column = 0;    ///< 1-based column, 0 if unknown
};

/// Bad input rejected before it changed any state; the message names file:line:column, key and allowed values.
class InputError : public std::runtime_error {
 public:
  /// `problem` says what is wrong; `key` is the key path or argument; `allowed` lists what is accepted.
  InputError(std::string problem, std::string key = {}, std::string allowed = {}, SourceLocation where = {});

  /// What is wrong, without the location prefix.
  const std::string& problem() const { return problem_; }
  /// Key path (e.g. `children[1].age`) or argument name (e.g. `touch finger`); may be empty.
  const std::string& key() const { return key_; }
  /// The values that would have been accepted; may be empty.
  const std::string& allowed() const { return allowed_; }
  /// Where the bad value stands.
  const SourceLocation& where() const { return where_; }

 private:
  std::string problem_;
  std::string key_;
  std::string allowed_;
  SourceLocation where_;
};

/// Formats "file:line:column: key 'k': problem (allowed: a)" leaving out the parts that are empty.
std::string format_input_error(const std::string& problem, const std::string& key, const std::string& allowed,
                               const SourceLocation& where);

}  // namespace freeplay
