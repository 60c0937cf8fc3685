#include "freeplay/core/error.hpp"
#include "freeplay/policies/play_policy.hpp"

namespace freeplay::policies {

/// `idle`: the robot is present (it stands at the table) but never acts.
class IdlePolicy final : public PlayPolicy {
 public:
  /// Takes no parameters.
  explicit IdlePolicy(const YAML::Node& params) {
    if (params.IsDefined() && !params.IsNull() && params.size() > 0) {
      throw InputError("the idle policy takes no parameters", "robot.params", "{}");
    }
  }
  std::string name() const override { return "idle"; }
  void reset(const PolicyContext& /*context*/, Rng /*rng*/) override {}
  std::vector<Action> decide(const Observation& /*observation*/) override { return {}; }
};

FREEPLAY_REGISTER_POLICY(IdlePolicy, "idle", "present at the table, does nothing");

}  // namespace freeplay::policies
