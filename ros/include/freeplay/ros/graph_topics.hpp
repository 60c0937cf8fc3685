#pragma once
// The tick topics `freeplay serve` publishes as the game and core nodes: recording::TickTopics with the live graph's
// streams (kLiveGraphStreams), stamped on the graph's wall-clock time base and serialised for SandtrayGraph::publish.

#include <cstdint>
#include <optional>
#include <vector>

#include "freeplay/recording/tick_topics.hpp"
#include "freeplay/ros/graph.hpp"

namespace freeplay::ros_live {

/// The live graph's messages of each tick of one episode.
class GraphTopics {
 public:
  /// The topics of the episode with root `seed`; sandtray time 0 is ROS time `origin_ns`; `sim_robot`: our own
  /// move_sandbox_items streams `/poses` and the trajectory (not with an external robot); `arm_reach_m` places the Nao.
  GraphTopics(std::uint64_t seed, std::uint64_t origin_ns, bool sim_robot, double arm_reach_m);

  /// The tick's messages in the order the publishers send them (recording::TickTopics::tick), ready to publish.
  std::vector<ros_graph::SerializedMessage> tick(const runner::EpisodeSnapshot& snapshot);
  /// The real topics event `e` of the tick `t` goes out on (recording::TickTopics::event), ready to publish.
  std::vector<ros_graph::SerializedMessage> event(double t, const Event& e) const;
  /// The topics these ticks send, to advertise up front (no bytes).
  std::vector<ros_graph::SerializedMessage> declarations() const;
  /// Sets (or, with nullopt, stops) the `arm_reach` frame.
  void set_arm_reach(const std::optional<runner::ReachDisc>& reach) { topics_.set_arm_reach(reach); }

 private:
  std::vector<ros_graph::SerializedMessage> serialized(const std::vector<recording::TopicMessage>& messages) const;

  std::uint64_t origin_ns_;
  unsigned streams_;
  recording::TickTopics topics_;
};

}  // namespace freeplay::ros_live
