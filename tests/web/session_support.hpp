#pragma once
// Scenarios and options for the web tests' served sessions.

#include <filesystem>
#include <string>

#include "freeplay/core/yaml_schema.hpp"
#include "freeplay/scenario/scenario.hpp"
#include "freeplay/web/web_session.hpp"

namespace freeplay::web::test_session {

/// The scenario of the YAML `text` (named test.yaml in errors).
inline scenario::Scenario scenario(const std::string& text) {
  return scenario::scenario_from_document(parse_yaml(text, "test.yaml"));
}

/// A session on an ephemeral loopback port at `rate`× real time that writes into the emptied temporary folder
/// `folder` and closes when its episode ends.
inline WebSessionOptions options(const std::string& folder, double rate) {
  const auto out = std::filesystem::temp_directory_path() / folder;
  std::filesystem::remove_all(out);
  WebSessionOptions options;
  options.server.port = 0;
  options.rate = rate;
  options.out = out;
  options.linger = false;
  return options;
}

}  // namespace freeplay::web::test_session
