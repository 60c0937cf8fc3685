// One episode, three fronts: the bag the recorder writes, the messages `freeplay serve` publishes on the live graph
// and the web page's Foxglove channels carry the same messages with the same stamps in the same order on every
// stream they share, since all three take them from recording::TickTopics.

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <rosbag/view.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <map>
#include <set>

#include "freeplay/core/yaml_schema.hpp"
#include "freeplay/recording/bag_recorder.hpp"
#include "freeplay/ros/graph_topics.hpp"
#include "freeplay/runner/episode.hpp"
#include "freeplay/web/foxglove.hpp"

namespace freeplay {
namespace {

constexpr std::uint64_t kOriginNs = static_cast<std::uint64_t>(recording::kEpochS) * 1000000000ULL;  // the bag's

/// One message as a subscriber sees it.
struct Seen {
  std::uint64_t stamp_ns = 0;  ///< when it was sent (0: the front does not say)
  std::string bytes;           ///< the serialised message
};

/// Messages by stream: the topic, and for /tf the first child frame (one broadcaster each).
using Streams = std::map<std::string, std::vector<Seen>>;

std::string stream_of(const std::string& topic, const std::string& bytes) {
  if (topic != recording::topics::kTf) return topic;
  recording::msg::TFMessage tf;
  std::string copy = bytes;
  ros::serialization::IStream in(reinterpret_cast<std::uint8_t*>(copy.data()), static_cast<std::uint32_t>(copy.size()));
  ros::serialization::deserialize(in, tf);
  return topic + ":" + (tf.transforms.empty() ? std::string() : recording::std_string(tf.transforms[0].child_frame_id));
}

void add(Streams& streams, const std::string& topic, std::uint64_t stamp_ns, std::string bytes) {
  auto name = stream_of(topic, bytes);
  streams[name].push_back({stamp_ns, std::move(bytes)});
}

/// The live graph's and the Foxglove channels' messages of every tick, each front as it runs in a session.
class Fronts final : public runner::EpisodeObserver {
 public:
  Streams graph, foxglove;

  void begin(const runner::EpisodeInfo& info) override {
    const double reach = info.scenario->robot.arm_reach_m;
    graph_ = std::make_unique<ros_live::GraphTopics>(info.seed, kOriginNs, true, reach);
    foxglove_ = std::make_unique<web::FoxgloveTopics>(info.seed, kOriginNs, reach);
  }

  void observe(const runner::EpisodeSnapshot& s) override {
    for (const auto& m : graph_->tick(s)) add(graph, m.topic, 0, std::string(m.bytes->begin(), m.bytes->end()));
    for (const auto& e : s.new_events) {  // the live graph publishes the tick's events after its topics
      for (const auto& m : graph_->event(s.t, e)) add(graph, m.topic, 0, std::string(m.bytes->begin(), m.bytes->end()));
    }
    for (const auto& m : foxglove_->tick(s)) add(foxglove, topic_of(m.channel), m.stamp_ns, *m.payload);
  }

 private:
  static std::string topic_of(int channel) {
    for (const auto& c : web::foxglove_channels({}, true)) {
      if (c.id == channel) return c.topic;
    }
    return "";
  }

  std::unique_ptr<ros_live::GraphTopics> graph_;
  std::unique_ptr<web::FoxgloveTopics> foxglove_;
};

/// Every message of the bag, by stream, in bag-time order (as `rosbag play` sends them).
Streams read_bag(const std::filesystem::path& path) {
  recording::Bag bag;
  bag.open(path.string(), rosbag::bagmode::Read);
  Streams out;
  for (const auto& m : rosbag::View(bag.get())) {
    std::string bytes(m.size(), '\0');
    ros::serialization::OStream stream(reinterpret_cast<std::uint8_t*>(bytes.data()), m.size());
    m.write(stream);
    add(out, m.getTopic(), m.getTime().toNSec(), std::move(bytes));
  }
  return out;
}

/// "" when `a` and `b` hold the same messages in the same order (with `stamps`, sent at the same times), else where
/// they first differ.
std::string first_difference(const std::vector<Seen>& a, const std::vector<Seen>& b, bool stamps) {
  if (a.size() != b.size()) return fmt::format("{} messages against {}", a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].bytes != b[i].bytes) return fmt::format("message {} differs", i);
    if (stamps && a[i].stamp_ns != b[i].stamp_ns) {
      return fmt::format("message {} sent at {} ns against {} ns", i, a[i].stamp_ns, b[i].stamp_ns);
    }
  }
  return "";
}

/// The streams `a` and `b` both carry.
std::set<std::string> shared(const Streams& a, const Streams& b) {
  std::set<std::string> out;
  for (const auto& [name, messages] : a) {
    if (b.count(name) != 0) out.insert(name);
  }
  return out;
}

TEST(TickTopicsFronts, TheBagTheLiveGraphAndFoxgloveCarryTheSameMessagesStampsAndOrder) {
  const auto scenario = scenario::scenario_from_document(parse_yaml(
      "name: fronts\ncondition: child-robot\nrecord: true\n"
      "protocol: {greeting_s: 0.5, tutorial_s: 0.5, freeplay_cap_s: 20, debriefing_s: 0.5}\n",
      "fronts.yaml"));
  const auto dir = std::filesystem::temp_directory_path() / fmt::format("freeplay-fronts-{}", ::getpid());
  std::filesystem::remove_all(dir);
  runner::EpisodeObservers observers;
  observers.push_back(std::make_unique<recording::BagRecorder>(dir / "sessions", scenario.recording));
  auto fronts = std::make_unique<Fronts>();
  const Fronts& out = *fronts;
  observers.push_back(std::move(fronts));
  const std::atomic<bool> stop{false};
  runner::run_episode({.scenario = scenario, .seed = 11, .stop = stop, .id = "fronts-0000"},
                      runner::observed_by(observers));
  const auto bag = read_bag(dir / "sessions" / "fronts-0000" / "freeplay.bag");

  // The bag and the live graph: the same bytes (header stamps included) in the same order on every shared stream.
  const auto bag_graph = shared(bag, out.graph);
  for (const auto* stream : {"/tf:zebra", "/tf:girl", "/tf:camera_purple_link", "/footprints", "/zones",
                             "/sandtray/background/image/compressed", "/joint_states", "/poses", "/speech",
                             "/sandtray/signals/start_tutorial", "/sandtray/signals/start_freeplay",
                             "/sandtray/signals/blank_interface"}) {
    EXPECT_EQ(bag_graph.count(stream), 1U) << stream << " is not on both the bag and the live graph";
  }
  for (const auto& name : bag_graph) EXPECT_EQ(first_difference(bag.at(name), out.graph.at(name), false), "") << name;
  // The bag and Foxglove: the same bytes, and each message's Foxglove stamp is its bag time.
  const auto bag_foxglove = shared(bag, out.foxglove);
  for (const auto* stream : {"/tf:zebra", "/tf:base_link", "/footprints", "/zones", "/sandtray/background/image/compressed",
                             "/joint_states"}) {
    EXPECT_EQ(bag_foxglove.count(stream), 1U) << stream << " is not on both the bag and Foxglove";
  }
  for (const auto& name : bag_foxglove) EXPECT_EQ(first_difference(bag.at(name), out.foxglove.at(name), true), "") << name;
  // Each front carries its declared streams only: the live graph adds /map and the background's raw image; the bag
  // the head trackers; Foxglove none of its own.
  EXPECT_EQ(out.graph.count("/map"), 1U);
  EXPECT_EQ(out.graph.count("/sandtray/background/image"), 1U);
  EXPECT_EQ(out.graph.count("/tf:child_purple_0"), 0U);
  EXPECT_EQ(bag.count("/tf:child_purple_0"), 1U);
  EXPECT_EQ(bag.count("/map"), 0U);
  for (const auto& [name, messages] : out.foxglove) EXPECT_EQ(bag.count(name), 1U) << name;
  // The footprints, once, about 1 s after the start on all three (free-play-sandbox.md §2.2).
  ASSERT_EQ(bag.at("/footprints").size(), 1U);
  EXPECT_EQ(recording::publication_tick(static_cast<double>(bag.at("/footprints")[0].stamp_ns - kOriginNs) * 1e-9), 10);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace freeplay
