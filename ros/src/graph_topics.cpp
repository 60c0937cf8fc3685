#include "freeplay/ros/graph_topics.hpp"

namespace freeplay::ros_live {

namespace {

recording::TickTopicsOptions live_options(std::uint64_t origin_ns, bool sim_robot, double arm_reach_m) {
  recording::TickTopicsOptions options;
  options.streams = recording::kLiveGraphStreams;
  if (!sim_robot) options.streams &= ~unsigned{recording::kFingerPoses | recording::kTrajectory};
  options.origin_ns = origin_ns;
  options.arm_reach_m = arm_reach_m;
  return options;
}

// The graph's plain-data form (graph.hpp holds standard types only) of a topic and its bytes.
ros_graph::SerializedMessage graph_message(recording::TopicDeclaration d,
                                           std::shared_ptr<const std::vector<std::uint8_t>> bytes) {
  return {std::move(d.topic), std::move(d.datatype), std::move(d.md5sum), std::move(d.definition), d.latched,
          std::move(bytes)};
}

}  // namespace

GraphTopics::GraphTopics(std::uint64_t seed, std::uint64_t origin_ns, bool sim_robot, double arm_reach_m)
    : origin_ns_(origin_ns),
      streams_(live_options(origin_ns, sim_robot, arm_reach_m).streams),
      topics_(seed, live_options(origin_ns, sim_robot, arm_reach_m)) {}

std::vector<ros_graph::SerializedMessage> GraphTopics::declarations() const {
  std::vector<ros_graph::SerializedMessage> out;
  for (auto& d : recording::declared_topics(streams_)) out.push_back(graph_message(std::move(d), nullptr));
  return out;
}

std::vector<ros_graph::SerializedMessage> GraphTopics::tick(const runner::EpisodeSnapshot& snapshot) {
  return serialized(topics_.tick(snapshot));
}

std::vector<ros_graph::SerializedMessage> GraphTopics::event(double t, const Event& e) const {
  return serialized(topics_.event(t, e));
}

std::vector<ros_graph::SerializedMessage> GraphTopics::serialized(const std::vector<recording::TopicMessage>& messages) const {
  std::vector<ros_graph::SerializedMessage> out;
  for (const auto& m : messages) {
    auto s = recording::serialize(m, origin_ns_);
    out.push_back(graph_message(std::move(s.declaration), std::move(s.bytes)));
  }
  return out;
}

}  // namespace freeplay::ros_live
