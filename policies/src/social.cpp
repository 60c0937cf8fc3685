#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <map>

#include "freeplay/core/error.hpp"
#include "freeplay/core/settings_archive.hpp"
#include "freeplay/policies/asocial.hpp"
#include "freeplay/policies/play_policy.hpp"

namespace freeplay::policies {

namespace {

/// The social policy's `robot.params`.
struct SocialParams {
  double reaction_delay_s = 0.8;    ///< delay before reacting to a child's move
  double praise_probability = 0.5;  ///< chance to praise a child's move
  double join_probability = 0.6;    ///< chance to join a child's move with a move
  double idle_proposal_s = 20.0;    ///< child idle this long → propose an idea
  double disengaged_s = 45.0;       ///< child idle this long → encourage
  double turn_timeout_s = 15.0;     ///< wait this long for the child's turn
  double join_offset_m = 0.06;      ///< distance from the child's item
  double min_move_m = 0.02;         ///< displacement that counts as a move

  /// The keys of the social policy's `robot.params`.
  template <typename Archive>
  void visit(Archive& a) {
    a.field("reaction_delay_s", reaction_delay_s, Schema::number(0, 10), "delay before reacting to a child's move");
    a.field("praise_probability", praise_probability, Schema::number(0, 1), "chance to praise a child's move");
    a.field("join_probability", join_probability, Schema::number(0, 1), "chance to join a child's move with a move");
    a.field("idle_proposal_s", idle_proposal_s, Schema::number(1, 600), "child idle this long → propose an idea");
    a.field("disengaged_s", disengaged_s, Schema::number(1, 600), "child idle this long → encourage");
    a.field("turn_timeout_s", turn_timeout_s, Schema::number(0, 600), "wait this long for the child's turn");
    a.field("join_offset_m", join_offset_m, Schema::number(0.02, 0.2), "distance from the child's item");
    a.field("min_move_m", min_move_m, Schema::number(0.005, 0.2), "displacement that counts as a move");
  }
};

/// A child's move as the robot infers it from the touch frames and item TF.
struct ObservedMove {
  std::string item;
  Vec2 from;
  Vec2 to;
};

/// `social`: our responsive policy — social gaze, joint attention, contingent reactions (joins, imitates,
/// complements, praises), turn-taking, ideas when the child is idle, encouragement when it disengages; it never
/// takes an item a child is holding.
class SocialPolicy final : public PlayPolicy {
 public:
  /// Parameters: SocialParams (all optional).
  explicit SocialPolicy(const YAML::Node& params)
      : params_(read_unvalidated_settings<SocialParams>(params, "robot.params")) {}

  std::string name() const override { return "social"; }
  bool perceives_children() const override { return true; }

  void reset(const PolicyContext& context, Rng rng) override {
    rng_ = rng;
    seat_ = context.robot_seat;
    grabbed_at_.clear();
    pending_.reset();
    react_at_ = 0.0;
    moving_ = false;
    my_turn_done_at_ = -1e9;
    child_moved_since_my_turn_ = true;
    last_proposal_ = -1e9;
    last_encouragement_ = -1e9;
    looking_at_.clear();
  }

  std::vector<Action> decide(const Observation& o) override {
    std::vector<Action> actions;
    track_child_moves(o);
    social_gaze(o, actions);
    const auto* child = primary_child(o);
    const double child_idle = child != nullptr ? child->seconds_since_touch : 1e9;

    if (pending_ && o.t >= react_at_ && !moving_) {
      react_to(*pending_, o, actions);
      pending_.reset();
    } else if (!moving_ && !pending_) {
      if (child_idle >= params_.disengaged_s && o.t - last_encouragement_ > params_.disengaged_s) {
        last_encouragement_ = o.t;
        actions.push_back(Say{encouragement(o), child_seat(o)});
        propose_move(o, actions);  // show by example
      } else if (child_idle >= params_.idle_proposal_s && o.t - last_proposal_ > params_.idle_proposal_s) {
        last_proposal_ = o.t;
        actions.push_back(Say{rng_.bernoulli(0.5) ? "Shall we build a zoo? The animals need their homes!"
                                                  : "Let's tell a story: the lion is looking for his friends!",
                              child_seat(o)});
      } else if (child_moved_since_my_turn_ || o.t - my_turn_done_at_ > params_.turn_timeout_s) {
        // Turn-taking: after my move, wait for the child's turn (or a timeout) before moving again.
        if (o.t - my_turn_done_at_ > 4.0 && rng_.bernoulli(0.02)) propose_move(o, actions);
      }
    }
    return actions;
  }

  void on_result(const ActionResult& result) override {
    if (result.kind == ActionResult::Kind::SpeechFinished) return;
    moving_ = false;
    my_turn_done_at_ = last_t_;
    child_moved_since_my_turn_ = false;
  }

 private:
  const PerceivedChild* primary_child(const Observation& o) const {
    for (const auto& c : o.children) {
      if (c.seat != seat_) return &c;
    }
    return nullptr;
  }

  std::string child_seat(const Observation& o) const {
    const auto* c = primary_child(o);
    return c != nullptr ? c->seat : "";
  }

  // Infers child moves: an item touched by a child, then released, displaced by more than min_move_m.
  void track_child_moves(const Observation& o) {
    last_t_ = o.t;
    for (const auto& item : o.items) {
      const auto it = grabbed_at_.find(item.name);
      if (item.touched_by_child && it == grabbed_at_.end()) {
        grabbed_at_[item.name] = item.pose.position();
      } else if (!item.touched_by_child && it != grabbed_at_.end()) {
        const Vec2 from = it->second;
        grabbed_at_.erase(it);
        if ((item.pose.position() - from).norm() >= params_.min_move_m) {
          pending_ = ObservedMove{item.name, from, item.pose.position()};
          react_at_ = o.t + params_.reaction_delay_s;
          child_moved_since_my_turn_ = true;
        }
      }
    }
  }

  void social_gaze(const Observation& o, std::vector<Action>& actions) {
    std::string target;
    for (const auto& c : o.children) {
      if (c.face_detected && (c.addressing_robot || c.gaze == PerceivedGaze::Robot)) target = "child:" + c.seat;
    }
    if (target.empty()) {
      for (const auto& c : o.children) {
        if (c.moving_item) {
          if (const auto* item = o.item(*c.moving_item)) {
            target = "item:" + item->name;  // joint attention to the handled item
            if (target != looking_at_) {
              looking_at_ = target;
              actions.push_back(LookAt{Eigen::Vector3d(item->pose.x, item->pose.y, 0.0), std::nullopt});
            }
            return;
          }
        }
      }
    }
    if (!target.empty() && target != looking_at_) {
      looking_at_ = target;
      actions.push_back(LookAt{std::nullopt, target.substr(6)});
    }
  }

  bool held_by_child(const Observation& o, const std::string& name) const {
    const auto* item = o.item(name);
    if (item == nullptr || item->touched_by_child) return true;
    for (const auto& c : o.children) {
      if (c.moving_item && *c.moving_item == name) return true;
    }
    return grabbed_at_.count(name) != 0;
  }

  bool reachable(const Observation& o, const Vec2& p) const {
    return !o.self.arm_reach_known || (p - o.self.arm_reach_centre).norm() < o.self.arm_reach_radius;
  }

  // Joins/imitates/complements the child's move: brings an item with a shared habitat next to the child's item.
  void react_to(const ObservedMove& move, const Observation& o, std::vector<Action>& actions) {
    if (rng_.bernoulli(params_.praise_probability)) {
      static const char* praises[] = {"Great idea!", "I like where you put the {}!", "Well done!",
                                      "Oh, the {} looks happy there!"};
      const auto* text = praises[rng_.uniform_int(0, 3)];
      actions.push_back(Say{fmt::format(fmt::runtime(text), move.item), child_seat(o)});
    }
    if (!rng_.bernoulli(params_.join_probability)) return;
    const auto& habitats = asocial_habitats();
    const auto moved = habitats.find(move.item);
    std::vector<std::string> candidates;
    for (const auto& [name, colours] : habitats) {
      if (name == move.item || held_by_child(o, name)) continue;
      const auto* item = o.item(name);
      if (item == nullptr || !reachable(o, item->pose.position())) continue;
      const bool shares = moved != habitats.end() &&
                          std::any_of(colours.begin(), colours.end(), [&](const auto& c) {
                            return std::find(moved->second.begin(), moved->second.end(), c) != moved->second.end();
                          });
      if (shares) candidates.push_back(name);
    }
    if (candidates.empty()) return;
    const auto& chosen = candidates[static_cast<std::size_t>(rng_.uniform_int(0, static_cast<std::int64_t>(candidates.size()) - 1))];
    const double angle = rng_.uniform(0.0, 2.0 * 3.141592653589793);
    Vec2 target = move.to + params_.join_offset_m * Vec2(std::cos(angle), std::sin(angle));
    target.x() = std::clamp(target.x(), 0.03, 0.50);
    target.y() = std::clamp(target.y(), -0.305, -0.03);
    if (!reachable(o, target)) return;
    actions.push_back(LookAt{Eigen::Vector3d(target.x(), target.y(), 0.0), std::nullopt});
    actions.push_back(MoveItem{chosen, target});
    moving_ = true;
  }

  // Takes a turn by example: puts a free item into one of its habitats (as the asocial policy would).
  void propose_move(const Observation& o, std::vector<Action>& actions) {
    Observation free_items = o;
    free_items.items.erase(std::remove_if(free_items.items.begin(), free_items.items.end(),
                                          [&](const auto& i) { return held_by_child(o, i.name); }),
                           free_items.items.end());
    AsocialPolicy chooser(YAML::Node{});
    chooser.reset({}, Rng(rng_()));
    if (auto move = chooser.choose_move(free_items)) {
      actions.push_back(*move);
      moving_ = true;
    }
  }

  std::string encouragement(const Observation& o) {
    static const char* lines[] = {"Do you want to help me with the {}?", "Your turn! Where should the {} go?",
                                  "I wonder where the {} lives. Can you show me?"};
    const auto& items = o.items;
    const std::string item = items.empty() ? std::string("animals")
                                           : items[static_cast<std::size_t>(rng_.uniform_int(0, static_cast<std::int64_t>(items.size()) - 1))].name;
    return fmt::format(fmt::runtime(lines[rng_.uniform_int(0, 2)]), item);
  }

  SocialParams params_;
  Rng rng_{0};
  std::string seat_ = "yellow";
  std::map<std::string, Vec2> grabbed_at_;
  std::optional<ObservedMove> pending_;
  double react_at_ = 0.0;
  bool moving_ = false;
  double my_turn_done_at_ = -1e9;
  bool child_moved_since_my_turn_ = true;
  double last_proposal_ = -1e9;
  double last_encouragement_ = -1e9;
  double last_t_ = 0.0;
  std::string looking_at_;
};

}  // namespace

FREEPLAY_REGISTER_POLICY(SocialPolicy, "social",
                         "responsive: social gaze, joint attention, joins and praises, turn-taking, ideas");

}  // namespace freeplay::policies
