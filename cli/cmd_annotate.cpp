// `freeplay annotate EVENTS.jsonl`: the coder on a recorded event log (live, replayed or from bag children).

#include <fmt/format.h>

#include <iostream>
#include <memory>

#include "command_registry.hpp"
#include "freeplay/agents/params.hpp"
#include "freeplay/core/assets.hpp"
#include "freeplay/core/atomic_file.hpp"
#include "freeplay/runner/event_coding.hpp"

namespace freeplay::cli {
namespace {

struct AnnotateOptions {
  std::string events;
  std::string output;
  std::string params_file;
};

void annotate(const AnnotateOptions& o) {
  const agents::ChildModelParams params = o.params_file.empty()
                                              ? agents::default_child_model_params()
                                              : agents::load_child_model_params(o.params_file);
  const auto coded = runner::code_event_log(runner::read_event_log(o.events), params.coder);
  const std::string yaml = agents::to_pinsoro_yaml(
      coded, 0.0, fmt::format("Social engagement coded by freeplay-sim's coder from {}", o.events));
  if (o.output.empty()) {
    std::cout << yaml;
  } else {
    write_file_atomically(o.output, yaml);
  }
  for (const auto& [seat, timeline] : {std::pair{"purple", coded.purple}, std::pair{"yellow", coded.yellow}}) {
    if (!timeline) continue;
    const auto shares = agents::label_shares(*timeline, agents::Axis::SocialEngagement);
    std::string line = fmt::format("{}:", seat);
    for (std::size_t j = 0; j < agents::label_count(agents::Axis::SocialEngagement); ++j) {
      line += fmt::format(" {} {:.3f}", agents::label_name(agents::Axis::SocialEngagement, j), shares[j]);
    }
    std::cerr << line << "\n";
  }
}

const RegisterCommand annotate_command(46, [](CLI::App& program) {
  auto o = std::make_shared<AnnotateOptions>();
  auto* cmd = program.add_subcommand(
      "annotate",
      "Code the social engagement of both players of a recorded event log (events/<episode>.jsonl) with the coder's "
      "rules, as the human coder of PInSoRo did; writes PInSoRo annotation YAML");
  cmd->add_option("EVENTS", o->events, "An episode's event log (JSON Lines)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--out", o->output, "Write the YAML here (atomically) instead of standard output");
  cmd->add_option("--params", o->params_file, "Child-model YAML whose `coder:` rules to use (default: shipped)");
  cmd->callback([o] { annotate(*o); });
});

}  // namespace
}  // namespace freeplay::cli
