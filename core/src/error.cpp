#include "freeplay/core/error.hpp"

#include <fmt/format.h>

namespace freeplay {

std::string format_input_error(const std::string& problem, const std::string& key, const std::string& allowed,
                               const SourceLocation& where) {
  std::string out;
  if (!where.file.empty()) {
    out += where.file;
    if (where.line > 0) out += fmt::format(":{}", where.line);
    if (where.column > 0) out += fmt::format(":{}", where.column);
    out += ": ";
  }
  if (!key.empty()) out += fmt::format("'{}': ", key);
  out += problem;
  if (!allowed.empty()) out += fmt::format(" (allowed: {})", allowed);
  return out;
}

InputError::InputError(std::string problem, std::string key, std::string allowed, SourceLocation where)
    : std::runtime_error(format_input_error(problem, key, allowed, where)),
      problem_(std::move(problem)),
      key_(std::move(key)),
      allowed_(std::move(allowed)),
      where_(std::move(where)) {}

}  // namespace freeplay
