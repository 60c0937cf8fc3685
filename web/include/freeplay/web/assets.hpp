#pragma once
// The page's files (web/assets/: HTML, JS, CSS), compiled into the binary so the page works offline from any
// install location.

#include <optional>
#include <string_view>

namespace freeplay::web {

/// One embedded file.
struct Asset {
  std::string_view content_type;  ///< e.g. "text/html; charset=utf-8"
  std::string_view body;          ///< the file's bytes
};

/// The embedded file served at `path` ("/" is index.html), or nullopt.
std::optional<Asset> find_asset(std::string_view path);

}  // namespace freeplay::web
