#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <atomic>
#include <fstream>
#include <thread>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "freeplay/core/error.hpp"
#include "freeplay/recording/bag_recorder.hpp"
#include "freeplay/recording/audio.hpp"
#include "freeplay/recording/audio_data.hpp"
#include "audio_checks.hpp"
#include "test_dirs.hpp"
#include "freeplay/recording/bag_description.hpp"
#include "freeplay/recording/camera_topics.hpp"
#include "freeplay/recording/pinsoro_csv.hpp"
#include "freeplay/agents/labels.hpp"
#include "freeplay/recording/publishers.hpp"
#include "freeplay/recording/replay.hpp"
#include "freeplay/recording/session_videos.hpp"
#include "freeplay/recording/ros_messages.hpp"
#include "freeplay/runner/episode.hpp"
#include "freeplay/sim/sandtray.hpp"

using namespace freeplay;
using namespace freeplay::recording;
using freeplay::recording::test_dirs::file_bytes;
using freeplay::recording::test_dirs::fresh_dir;

namespace {

const runner::SharedModels& models() { return runner::SharedModels::shipped(); }

// The tiny protocol of the brief: greeting 1 s, tutorial 1 s, free play 10 s, debriefing 1 s; `record` is the
// scenario's record setting.
scenario::Scenario tiny(const std::string& condition, const std::string& extra = "", double freeplay_cap_s = 10,
                      const std::string& record = "true") {
  return scenario::scenario_from_document(parse_yaml(
      fmt::format("name: tiny\ncondition: {}\nrecord: {}\n"
                  "protocol: {{greeting_s: 1, tutorial_s: 1, freeplay_cap_s: {}, debriefing_s: 1}}\n{}",
                  condition, record, freeplay_cap_s, extra),
      "tiny.yaml"));
}

// A synthetic colour frame that changes with time (smooth, so JPEG keeps it close).
cv::Mat synthetic_rgb(double t, int width = 64, int height = 48) {
  cv::Mat rgb(height, width, CV_8UC3);
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) {
      rgb.at<cv::Vec3b>(r, c) = cv::Vec3b(static_cast<unsigned char>(c * 3), static_cast<unsigned char>(r * 4),
                                          static_cast<unsigned char>(static_cast<int>(t * 10) % 200));
    }
  }
  return rgb;
}

cv::Mat synthetic_depth(double t, int width = 32, int height = 24) {
  cv::Mat depth(height, width, CV_32FC1);
  for (int r = 0; r < height; ++r) {
    for (int c = 0; c < width; ++c) depth.at<float>(r, c) = static_cast<float>(0.5 + 0.01 * c + 0.001 * r + 0.0001 * t);
  }
  depth.at<float>(0, 0) = std::numeric_limits<float>::quiet_NaN();
  return depth;
}

stage::FramePack pack(const std::string& camera, double t, bool depth) {
  stage::FramePack f;
  f.camera = camera;
  f.stamp = t;
  f.rgb = synthetic_rgb(t);
  f.K = {64, 48, 50.0, 50.0, 32.0, 24.0};
  if (depth) {
    f.depth_m = synthetic_depth(t);
    f.K_depth = {32, 24, 25.0, 25.0, 16.0, 12.0};
  }
  f.sandtray_T_camera_optical.translation() = Eigen::Vector3d(-0.1, 0.02, 0.03);
  return f;
}

// Feeds the recorder synthetic camera frames (camera_purple at 30 Hz with depth) and remembers item poses.
struct SyntheticCameras final : runner::EpisodeObserver {
  runner::FrameSink* sink = nullptr;
  std::map<double, std::map<std::string, Vec2>> items;
  double last_t = 0.0;
  int frames = 0;
  void observe(const runner::EpisodeSnapshot& s) override {
    for (const auto& item : s.tray->items()) items[s.t][item.name] = item.pose.position();
    // Three frames per 10 Hz tick, at the tick and one and two thirds before it.
    for (int k = 2; k >= 0; --k) {
      const double t = s.t - k * (0.1 / 3.0);
      if (t <= last_t + 1e-9) continue;
      sink->write(pack("camera_purple", t, true));
      ++frames;
    }
    last_t = s.t;
  }
};

struct Recorded {
  std::filesystem::path run_dir;
  runner::EpisodeResult result;
  std::map<double, std::map<std::string, Vec2>> items;
  int frames = 0;
};

Recorded record_episode(const std::string& name, const std::string& condition, const std::string& extra = "",
                        std::uint64_t seed = 7, double freeplay_cap_s = 10, const std::string& record = "true") {
  Recorded out;
  out.run_dir = fresh_dir(name);
  const auto scenario = tiny(condition, extra, freeplay_cap_s, record);
  runner::EpisodeObservers observers;
  auto recorder = std::make_unique<BagRecorder>(out.run_dir / "sessions", scenario.recording);
  auto cameras = std::make_unique<SyntheticCameras>();
  cameras->sink = recorder.get();
  auto* cams = cameras.get();
  observers.push_back(std::move(recorder));
  observers.push_back(std::move(cameras));
  const std::atomic<bool> stop{false};
  out.result =
      runner::run_episode({.scenario = scenario, .seed = seed, .models = models(), .stop = stop, .id = "tiny-0000"},
                          runner::observed_by(observers));
  out.items = cams->items;
  out.frames = cams->frames;
  return out;
}

const Recorded& child_robot() {
  static const Recorded r = record_episode("cr", "child-robot");
  return r;
}

std::filesystem::path bag_path(const Recorded& r) { return r.run_dir / "sessions" / "tiny-0000" / "freeplay.bag"; }

bool have_python_rosbag() { return std::system("/usr/bin/python3 -c 'import rosbag' >/dev/null 2>&1") == 0; }

}  // namespace

TEST(BagRecorder, WritesTheSessionFolderAndTheRecordField) {
  const auto& r = child_robot();
  ASSERT_FALSE(r.result.aborted);
  const auto dir = r.run_dir / "sessions" / "tiny-0000";
  EXPECT_TRUE(std::filesystem::exists(dir / "freeplay.bag"));
  EXPECT_FALSE(std::filesystem::exists(dir / "freeplay.bag.active"));
  EXPECT_TRUE(std::filesystem::exists(dir / "freeplay.annotations.freeplay-sim.yaml"));
  EXPECT_EQ(r.result.record.value("recording", ""), "sessions/tiny-0000");
  const auto experiment = YAML::LoadFile((dir / "experiment.yaml").string());
  EXPECT_EQ(experiment["condition"].as<std::string>(), "childrobot");
  EXPECT_EQ(experiment["purple-participant"]["age"].as<int>(),
            r.result.record["children"]["purple"]["age"].get<int>());
  EXPECT_EQ(experiment["purple-participant"]["id"].as<std::string>(), "tiny-0000-p2");
  EXPECT_FALSE(experiment["yellow-participant"].IsDefined());
  EXPECT_FALSE(experiment["issues"].IsDefined());
  EXPECT_TRUE(experiment["markers"].IsMap());
  EXPECT_GT(experiment["timestamp"].as<std::uint64_t>(), 1500000000ULL * 1000000000ULL);
}

TEST(BagRecorder, TopicsTypesAndRatesAreTheRealOnes) {
  const auto& r = child_robot();
  const auto rec = read_session(bag_path(r));
  const std::map<std::string, std::string> expected = {
      {"/tf", "tf2_msgs/TFMessage"},
      {"/footprints", "visualization_msgs/MarkerArray"},
      {"/zones", "visualization_msgs/MarkerArray"},
      {"/sandtray/background/image/compressed", "sensor_msgs/CompressedImage"},
      {"camera_purple/rgb/image_raw/compressed", "sensor_msgs/CompressedImage"},
      {"camera_purple/rgb/camera_info", "sensor_msgs/CameraInfo"},
      {"camera_purple/depth/image_raw/compressedDepth", "sensor_msgs/CompressedImage"},
      {"camera_purple/depth/camera_info", "sensor_msgs/CameraInfo"},
      {"/joint_states", "sensor_msgs/JointState"},
      {"/freeplay/events", "std_msgs/String"},
      {"/freeplay/annotations", "std_msgs/String"},
      {"/speech", "std_msgs/String"},
      {"/sandtray/signals/start_freeplay", "std_msgs/Empty"},
      {"/freeplay/scenario", "std_msgs/String"},
      {"/freeplay/episode", "std_msgs/String"}};
  for (const auto& [topic, type] : expected) {
    ASSERT_TRUE(rec.topic_types.contains(topic)) << topic;
    EXPECT_EQ(rec.topic_types.at(topic), type) << topic;
  }
  const double duration = r.result.simulated_s;  // 13 s of protocol
  auto near_rate = [&](const std::string& topic, double hz) {
    const double expected_count = hz * duration;
    EXPECT_NEAR(static_cast<double>(rec.topic_counts.at(topic)), expected_count, 0.05 * expected_count) << topic;
  };
  near_rate("camera_purple/rgb/image_raw/compressed", 30);
  near_rate("camera_purple/depth/image_raw/compressedDepth", 30);
  near_rate("camera_purple/rgb/camera_info", 30);
  near_rate("/joint_states", 10);
  // One message per item, per touch, per head, for the camera links, the robot's focus and its links (10 Hz each),
  // and the camera's optical frames at 10 Hz.
  const double publishers = static_cast<double>(r.items.begin()->second.size()) + 5.0;
  EXPECT_GE(static_cast<double>(rec.topic_counts.at("/tf")), 0.95 * 10.0 * publishers * duration);
  EXPECT_EQ(rec.topic_counts.at("/footprints"), 1U);
  EXPECT_EQ(rec.topic_counts.at("/freeplay/annotations"), 1U);
  EXPECT_EQ(rec.topic_counts.at("/sandtray/background/image/compressed"), rec.topic_counts.at("/zones"));
  EXPECT_LE(static_cast<double>(rec.topic_counts.at("/sandtray/background/image/compressed")), 4.0 * duration + 1);
  EXPECT_EQ(rec.events.size(), r.result.events.size());  // every event of the log
}

TEST(BagRecorder, CameraFramesDecodeToWhatWasWritten) {
  const auto& r = child_robot();
  rosbag::Bag bag(bag_path(r).string());
  rosbag::View colour(bag, rosbag::TopicQuery("camera_purple/rgb/image_raw/compressed"));
  int checked = 0;
  for (const auto& m : colour) {
    const auto image = m.instantiate<msg::CompressedImage>();
    EXPECT_EQ(std_string(image->format), "rgb8; jpeg compressed bgr8");
    EXPECT_EQ(std_string(image->header.frame_id), "camera_purple_rgb_optical_frame");
    const double t = sandtray_time(image->header.stamp);
    cv::Mat diff;
    cv::absdiff(decode_colour(*image), synthetic_rgb(t), diff);
    EXPECT_LT(cv::mean(diff)[0] + cv::mean(diff)[1] + cv::mean(diff)[2], 6.0);  // JPEG q90 on a smooth image
    if (++checked == 5) break;
  }
  EXPECT_EQ(checked, 5);
  rosbag::View depth(bag, rosbag::TopicQuery("camera_purple/depth/image_raw/compressedDepth"));
  const auto image = depth.begin()->instantiate<msg::CompressedImage>();
  EXPECT_EQ(std_string(image->format), "16UC1; compressedDepth");
  ASSERT_GT(image->data.size(), 12U);
  for (int i = 0; i < 12; ++i) EXPECT_EQ(image->data[static_cast<std::size_t>(i)], 0) << "ConfigHeader byte " << i;
  EXPECT_EQ(image->data[12], 0x89);  // PNG signature after the 12-byte ConfigHeader
  EXPECT_EQ(image->data[13], 'P');
  const cv::Mat mm = decode_compressed_depth(*image);
  const cv::Mat expected = synthetic_depth(sandtray_time(image->header.stamp));
  EXPECT_EQ(mm.at<std::uint16_t>(0, 0), 0);  // NaN → no reading
  for (int r2 = 0; r2 < mm.rows; ++r2) {
    for (int c = (r2 == 0 ? 1 : 0); c < mm.cols; ++c) {
      ASSERT_EQ(mm.at<std::uint16_t>(r2, c), std::lround(static_cast<double>(expected.at<float>(r2, c)) * 1000.0));
    }
  }
  rosbag::View info(bag, rosbag::TopicQuery("camera_purple/rgb/camera_info"));
  const auto ci = info.begin()->instantiate<msg::CameraInfo>();
  EXPECT_EQ(ci->width, 64U);
  EXPECT_DOUBLE_EQ(ci->K[0], 50.0);
  EXPECT_EQ(std_string(ci->distortion_model), "plumb_bob");
}

TEST(BagRecorder, TfItemPosesEqualTheSandtray) {
  const auto& r = child_robot();
  const auto rec = read_session(bag_path(r));
  std::size_t compared = 0;
  for (const auto& [t, items] : r.items) {
    const auto it = rec.item_positions.find(publication_tick(t));
    ASSERT_NE(it, rec.item_positions.end()) << t;
    for (const auto& [name, p] : items) {
      ASSERT_TRUE(it->second.contains(name)) << name;
      EXPECT_EQ(it->second.at(name), p) << name << " at " << t;
      ++compared;
    }
  }
  EXPECT_GT(compared, 100U);
}

TEST(Replay, RecomputesIdenticalMetrics) {
  const auto& r = child_robot();
  const auto recomputed = recompute_metrics(read_session(bag_path(r)));
  const auto comparison = compare_with_record(recomputed, r.result.record);
  EXPECT_GT(comparison.size(), 30U);
  for (const auto& c : comparison) EXPECT_TRUE(c.equal) << c.name << ": bag " << c.replayed << " vs record " << c.recorded;
  EXPECT_TRUE(recomputed["extra"]["complete"].get<bool>());
}

// A session recorded with lz4 or bz2 chunks passes the bag check, which decompresses and walks every chunk, and
// replays to the same metrics.
TEST(Replay, RecomputesIdenticalMetricsFromCompressedChunks) {
  for (const std::string compression : {"lz4", "bz2"}) {
    const auto r = record_episode("replay-" + compression, "child-robot", "", 7, 10,
                                  fmt::format("{{bag: true, compression: {}}}", compression));
    EXPECT_NE(file_bytes(bag_path(r)).find("compression=" + compression), std::string::npos) << compression;
    const auto comparison = compare_with_record(recompute_metrics(read_session(bag_path(r))), r.result.record);
    EXPECT_GT(comparison.size(), 30U) << compression;
    for (const auto& c : comparison) EXPECT_TRUE(c.equal) << compression << " " << c.name;
  }
}

TEST(Replay, RecomputesIdenticalMetricsChildChild) {
  const auto r = record_episode("cc", "child-child");
  const auto recomputed = recompute_metrics(read_session(bag_path(r)));
  const auto comparison = compare_with_record(recomputed, r.result.record);
  EXPECT_GT(comparison.size(), 30U);
  for (const auto& c : comparison) EXPECT_TRUE(c.equal) << c.name << ": bag " << c.replayed << " vs record " << c.recorded;
  const auto experiment = YAML::LoadFile((r.run_dir / "sessions/tiny-0000/experiment.yaml").string());
  EXPECT_EQ(experiment["condition"].as<std::string>(), "childchild");
  EXPECT_EQ(experiment["yellow-participant"]["id"].as<std::string>(), "tiny-0000-y1");
}

TEST(Replay, RecomputesGazeDrawingPlannerAndExecutorMetricsOfALongSession) {
  // Five minutes of a social robot: moves, placements, mutual gaze, joint attention and drawings all happen.
  const auto r = record_episode("long", "child-robot", "robot: {policy: social}\n", 2, 300);
  const auto recomputed = recompute_metrics(read_session(bag_path(r)));
  const auto& m = recomputed["metrics"];
  EXPECT_GT(m["drawing_coverage"].get<double>(), 0.0);
  EXPECT_GT(m["mutual_gaze_s"].get<double>(), 0.0);
  EXPECT_GT(m["executor"]["placement_error_mm"].get<double>(), 0.0);
  EXPECT_GT(m["planner"]["path_length_m"].get<double>(), 0.0);
  const auto comparison = compare_with_record(recomputed, r.result.record);
  EXPECT_GT(comparison.size(), 40U);
  for (const auto& c : comparison) EXPECT_TRUE(c.equal) << c.name << ": bag " << c.replayed << " vs record " << c.recorded;
}

TEST(BagRecorder, PythonRosbagAndRosbagInfoReadTheBag) {
  if (!have_python_rosbag()) GTEST_SKIP() << "Debian's python3-rosbag is not installed (scripts/setup.sh)";
  const auto bag = bag_path(child_robot()).string();
  const auto script = fmt::format(
      "/usr/bin/python3 -c \"import rosbag, sys; b = rosbag.Bag('{}'); "
      "n = sum(1 for _ in b.read_messages(topics=['/tf'])); "
      "t = b.get_type_and_topic_info().topics; "
      "sys.exit(0 if n > 100 and t['/zones'].msg_type == 'visualization_msgs/MarkerArray' else 1)\"",
      bag);
  EXPECT_EQ(std::system(script.c_str()), 0);
  EXPECT_EQ(std::system(fmt::format("rosbag info {} >/dev/null", bag).c_str()), 0);
}

TEST(BagRecorder, PythonRosbagSeesTheRealNamesTypesLatchingAndFrequencies) {
  if (!have_python_rosbag()) GTEST_SKIP() << "Debian's python3-rosbag is not installed (scripts/setup.sh)";
  const auto& r = child_robot();
  const auto bag = bag_path(r);
  // free-play-sandbox.md §4.1: relative camera names, the cameras' ~30 Hz (±3 Hz), a /tf frequency (many publishers
  // with their own phases), the latched topics.
  const auto script = fmt::format(R"(
import rosbag, sys
b = rosbag.Bag('{}')
info = b.get_type_and_topic_info().topics
want = {{'/tf': 'tf2_msgs/TFMessage', '/footprints': 'visualization_msgs/MarkerArray',
        '/zones': 'visualization_msgs/MarkerArray',
        '/sandtray/background/image/compressed': 'sensor_msgs/CompressedImage',
        'camera_purple/rgb/image_raw/compressed': 'sensor_msgs/CompressedImage',
        'camera_purple/rgb/camera_info': 'sensor_msgs/CameraInfo',
        'camera_purple/depth/image_raw/compressedDepth': 'sensor_msgs/CompressedImage',
        'camera_purple/depth/camera_info': 'sensor_msgs/CameraInfo',
        'camera_purple/audio': 'audio_common_msgs/AudioData', 'camera_yellow/audio': 'audio_common_msgs/AudioData'}}
bad = []
for topic, kind in want.items():
    if topic not in info or info[topic].msg_type != kind: bad.append('type ' + topic)
for topic in ['camera_purple/rgb/image_raw/compressed', 'camera_purple/rgb/camera_info',
              'camera_purple/depth/image_raw/compressedDepth', 'camera_purple/depth/camera_info']:
    f = info[topic].frequency
    if f is None or abs(f - 30.5) > 3: bad.append('rate %s %s' % (topic, f))
for topic in ['camera_purple/audio', 'camera_yellow/audio']:
    f = info[topic].frequency
    if f is None or abs(f - 25.7) > 3: bad.append('rate %s %s' % (topic, f))
md5 = {{c.topic: c.md5sum for c in b._get_connections()}}
if md5['camera_purple/audio'] != 'f43a8e1b362b75baa741461b46adc7e0': bad.append('AudioData md5')
if info['/tf'].frequency is None or info['/tf'].frequency < 100: bad.append('tf rate %s' % info['/tf'].frequency)
if any(t.startswith('/camera') or t.startswith('/env_camera') for t in info): bad.append('leading slash')
latched = {{c.topic for c in b._get_connections() if c.header.get('latching') in (b'1', '1')}}
for topic in ['/footprints', '/zones', '/sandtray/background/image/compressed']:
    if topic not in latched: bad.append('not latched ' + topic)
print(bad)
sys.exit(1 if bad else 0)
)",
                                  bag.string());
  const auto file = r.run_dir / "check_rates.py";
  std::ofstream(file) << script;
  EXPECT_EQ(std::system(fmt::format("/usr/bin/python3 {}", file.string()).c_str()), 0);
  // freeplay.bag.yaml is what `rosbag info --yaml` says about the bag, but for the path line.
  const auto ours = r.run_dir / "ours.yaml";
  const auto theirs = r.run_dir / "theirs.yaml";
  ASSERT_EQ(std::system(fmt::format("tail -n +2 {} > {}", (bag.parent_path() / "freeplay.bag.yaml").string(),
                                    ours.string()).c_str()), 0);
  ASSERT_EQ(std::system(fmt::format("rosbag info --yaml --freq {} | tail -n +2 > {}", bag.string(), theirs.string()).c_str()),
            0);
  EXPECT_EQ(std::system(fmt::format("diff {} {}", ours.string(), theirs.string()).c_str()), 0);
}

TEST(Audio, EveryUtteranceIsHeardWhereTheEventsSayAndTheBagCarriesTheMp3) {
  const auto& r = child_robot();
  const auto dir = bag_path(r).parent_path();
  // The bag's chunks are the MP3 file, one 16 kHz 128 kbps MPEG-2 layer III frame each.
  std::vector<std::uint8_t> chunks;
  std::size_t messages = 0;
  {
    rosbag::Bag bag(bag_path(r).string());
    for (const auto& m : rosbag::View(bag, rosbag::TopicQuery("camera_purple/audio"))) {
      EXPECT_EQ(m.getDataType(), "audio_common_msgs/AudioData");
      const auto chunk = m.instantiate<msg::AudioData>();
      ASSERT_TRUE(chunk);
      ASSERT_GE(chunk->data.size(), 4U);
      if (chunk->data.size() == static_cast<std::size_t>(kMp3FrameBytes)) {
        EXPECT_EQ(chunk->data[0], 0xFF);
        EXPECT_EQ(chunk->data[1] & 0xF0, 0xF0);  // frame sync, MPEG-2 (bit 3 clear)
      }
      chunks.insert(chunks.end(), chunk->data.begin(), chunk->data.end());
      ++messages;
    }
  }
  auto bytes_of = [](const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  };
  EXPECT_EQ(chunks, bytes_of(dir / "audio" / "freeplay_camera_purple_audio.mp3"));
  EXPECT_NEAR(static_cast<double>(messages), r.result.simulated_s * kAudioRate / kMp3FrameSamples, 4.0);
  // A voice-activity check on the purple microphone finds every utterance that starts after a silence within 100 ms.
  const auto samples = read_wav(dir / "audio" / "freeplay_camera_purple_audio.wav");
  EXPECT_NEAR(static_cast<double>(samples.size()), r.result.simulated_s * kAudioRate, 2.0);
  EXPECT_GT(audio_checks::expect_utterances_heard(samples, r.result.events.events()), 0);
  // The chunks decode (LAME's decoder) to that sound, delayed by the codec: the speech is where the events say there.
  const auto decoded = decode_mp3(chunks);
  const std::size_t delay = audio_checks::delay_of(decoded, samples, 2000);
  EXPECT_NEAR(static_cast<double>(delay), 1105.0, 50.0);  // LAME's encoder (576 + 529 samples) and decoder delay
  ASSERT_GT(decoded.size(), delay + samples.size() - 2 * kMp3FrameSamples);
  EXPECT_GT(audio_checks::expect_utterances_heard(std::vector<float>(decoded.begin() + static_cast<std::ptrdiff_t>(delay), decoded.end()),
                                                  r.result.events.events()),
            0);
  // Deterministic per seed: the same episode gives the same sound.
  const auto again = record_episode("cr-again", "child-robot");
  EXPECT_EQ(bytes_of(dir / "audio" / "freeplay_camera_purple_audio.mp3"),
            bytes_of(again.run_dir / "sessions" / "tiny-0000" / "audio" / "freeplay_camera_purple_audio.mp3"));
}

TEST(BagRecorder, PublishersHaveTheirOwnPhaseAndSeededJitter) {
  PublisherClocks a(7), b(7), c(8);
  std::vector<double> first, second;
  for (int k = 0; k < 50; ++k) {
    const double t = k * kPublishTickS;
    first.push_back(a.publish("game/zebra", t));
    second.push_back(b.publish("game/zebra", t));
    const double other = a.publish("game/lion", t);
    EXPECT_NE(first.back(), other);
    EXPECT_NE(first.back(), c.publish("game/zebra", t));
    for (const double p : {first.back(), other}) {
      EXPECT_GT(p, t);
      EXPECT_LE(p, t + kMaxPublishDelayS);
      EXPECT_EQ(publication_tick(p), k);
    }
  }
  EXPECT_EQ(first, second);  // deterministic per seed
}

TEST(BagRecorder, SessionFolderHasTheDatasetFiles) {
  const auto& r = child_robot();
  const auto dir = bag_path(r).parent_path();
  EXPECT_TRUE(std::filesystem::exists(dir / "freeplay.bag.yaml"));
  std::ifstream md5(dir / "freeplay.bag.md5");
  std::string hash, name;
  md5 >> hash >> name;
  EXPECT_EQ(hash, md5_hex(dir / "freeplay.bag"));
  EXPECT_EQ(hash.size(), 32U);
  EXPECT_EQ(name, "freeplay.bag");
  const auto experiment = YAML::LoadFile((dir / "experiment.yaml").string());
  for (const char* key : {"timestamp", "condition", "purple-participant", "markers", "notes", "extras"}) {
    EXPECT_TRUE(experiment[key].IsDefined()) << key;
  }
  const int likert = experiment["extras"]["social-engagement"].as<int>();
  EXPECT_GE(likert, 1);
  EXPECT_LE(likert, 5);
  for (const char* key : {"id", "age", "gender", "details"}) EXPECT_TRUE(experiment["purple-participant"][key]) << key;
  const auto yaml = YAML::LoadFile((dir / "freeplay.bag.yaml").string());
  EXPECT_EQ(yaml["path"].as<std::string>(), "freeplay.bag");
  EXPECT_EQ(yaml["size"].as<std::uintmax_t>(), std::filesystem::file_size(dir / "freeplay.bag"));
}

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> out(1);
  for (const char c : line) {
    if (c == ',') {
      out.emplace_back();
    } else {
      out.back() += c;
    }
  }
  return out;
}

TEST(PinsoroCsv, RealHeaderInTheRealOrderAndOneRowPerFrameOfFreePlay) {
  const auto& columns = pinsoro_csv_columns();
  ASSERT_EQ(columns.size(), 449U);
  const std::vector<std::string> first = {"timestamp", "id", "condition", "annotators", "complete", "purple_child_age",
                                          "purple_child_gender", "yellow_child_age", "yellow_child_gender",
                                          "purple_frame_idx", "purple_child_face00_x", "purple_child_face00_y"};
  EXPECT_TRUE(std::equal(first.begin(), first.end(), columns.begin()));
  EXPECT_EQ(columns[9 + 1 + 140], "purple_child_skel00_x");
  EXPECT_EQ(columns[9 + 1 + 140 + 36], "purple_child_head_x");
  EXPECT_EQ(columns[9 + 1 + 140 + 36 + 6], "purple_child_gaze_x");
  EXPECT_EQ(columns[9 + 1 + 140 + 36 + 9], "purple_child_au01");
  EXPECT_EQ(columns[9 + 1 + 140 + 36 + 9 + 17], "purple_child_au45");
  EXPECT_EQ(columns[9 + 1 + 140 + 36 + 9 + 18], "purple_child_motion_intensity_avg");
  EXPECT_EQ(columns[218], "yellow_frame_idx");
  EXPECT_EQ(columns[427], "audio00");
  EXPECT_EQ(columns[443], "purple_child_task_engagement");
  EXPECT_EQ(columns[448], "yellow_child_social_attitude");

  const auto& r = child_robot();
  const auto dir = bag_path(r).parent_path();
  std::ifstream in(dir / "pinsoro-tiny-0000.csv");
  std::string line;
  ASSERT_TRUE(std::getline(in, line));
  EXPECT_EQ(split_csv_line(line), columns);
  std::size_t rows = 0;
  std::map<std::string, std::size_t> task;  // purple task-engagement label → rows
  while (std::getline(in, line)) {
    const auto fields = split_csv_line(line);
    ASSERT_EQ(fields.size(), 449U);
    EXPECT_EQ(fields[1], "tiny-0000");
    EXPECT_EQ(fields[2], "childrobot");
    EXPECT_EQ(fields[9], std::to_string(rows));
    EXPECT_FALSE(fields[9 + 1 + 140 + 36].empty());  // head pose
    EXPECT_FALSE(fields[9 + 1 + 2 * 30].empty());     // the nose (face point 30) in the purple camera
    EXPECT_FALSE(fields[9 + 1 + 140 + 2].empty());    // the neck
    EXPECT_TRUE(fields[218].empty());                 // the robot replaces the yellow child: yellow fields empty
    EXPECT_TRUE(fields[448].empty());
    ++task[fields[443]];
    ++rows;
  }
  const double freeplay_s = r.result.record["duration_s"].get<double>();
  EXPECT_NEAR(static_cast<double>(rows), 30.0 * freeplay_s, 3.0);
  // Label shares of the table's rows equal the run's label shares (to a frame or two).
  for (const auto& [label, share] : r.result.record["metrics"]["label_share"]["purple"].items()) {
    if (!task.contains(label) && share.get<double>() == 0.0) continue;
    const auto axis = agents::parse_label(label);
    if (!axis || axis->first != agents::Axis::TaskEngagement) continue;
    EXPECT_NEAR(static_cast<double>(task[label]) / static_cast<double>(rows), share.get<double>(), 3.0 / rows) << label;
  }
  // freeplay.poses.json: extract_poses' layout, one frame per table row and camera topic.
  const auto poses = nlohmann::json::parse(std::ifstream(dir / "freeplay.poses.json"));
  for (const char* topic : {"camera_purple/rgb/image_raw/compressed", "camera_yellow/rgb/image_raw/compressed",
                            "env_camera/qhd/image_color/compressed"}) {
    ASSERT_TRUE(poses.contains(topic)) << topic;
    const auto& frames = poses[topic]["frames"];
    EXPECT_EQ(frames.size(), rows) << topic;
    const auto& f = frames[frames.size() / 2];
    EXPECT_GT(f["ts"].get<double>(), 1.5e9);
    EXPECT_EQ(f["poses"]["1"].size(), 18U);
    EXPECT_EQ(f["poses"]["1"][0].size(), 3U);
    EXPECT_EQ(f["faces"]["1"].size(), 70U);
    EXPECT_EQ(f["hands"]["1"]["left"].size(), 21U);
    EXPECT_FALSE(f["poses"].contains("2"));  // no yellow child in a child-robot session
  }
  std::ifstream md5(dir / "pinsoro-tiny-0000.csv.md5");
  std::string hash;
  md5 >> hash;
  EXPECT_EQ(hash, md5_hex(dir / "pinsoro-tiny-0000.csv"));
}

namespace {

// Stops the episode after `ticks` snapshots (Ctrl-C), or copies the open bag (a kill) at that tick.
struct Interrupter final : runner::EpisodeObserver {
  std::atomic<bool>* stop = nullptr;
  std::filesystem::path copy_from, copy_to;
  int ticks = 0;
  int seen = 0;
  void observe(const runner::EpisodeSnapshot&) override {
    if (++seen != ticks) return;
    if (stop != nullptr) stop->store(true);
    if (!copy_to.empty()) std::filesystem::copy_file(copy_from, copy_to);
  }
};

}  // namespace

TEST(BagRecorder, CtrlCClosesTheBagAndMarksTheSessionIncomplete) {
  const auto dir = fresh_dir("abort");
  const auto scenario = tiny("child-robot");
  std::atomic<bool> stop{false};
  runner::EpisodeObservers observers;
  observers.push_back(std::make_unique<BagRecorder>(dir / "sessions", scenario.recording));
  auto interrupter = std::make_unique<Interrupter>();
  interrupter->stop = &stop;
  interrupter->ticks = 60;  // mid free play
  observers.push_back(std::move(interrupter));
  const auto result =
      runner::run_episode({.scenario = scenario, .seed = 7, .models = models(), .stop = stop, .id = "tiny-0000"},
                          runner::observed_by(observers));
  EXPECT_TRUE(result.aborted);
  const auto session = dir / "sessions" / "tiny-0000";
  ASSERT_TRUE(std::filesystem::exists(session / "freeplay.bag"));
  const auto rec = read_session(session);
  EXPECT_GT(rec.topic_counts.at("/tf"), 100U);
  EXPECT_TRUE(rec.annotations_yaml.empty());
  EXPECT_FALSE(recompute_metrics(rec)["extra"]["complete"].get<bool>());
  const auto experiment = YAML::LoadFile((session / "experiment.yaml").string());
  ASSERT_TRUE(experiment["issues"].IsSequence());
  EXPECT_NE(experiment["issues"][0].as<std::string>().find("incomplete"), std::string::npos);
}

TEST(BagRecorder, AKilledRecordingIsReindexable) {
  const auto dir = fresh_dir("kill");
  const auto scenario = tiny("child-robot", "");
  auto settings = scenario.recording;
  settings.chunk_kb = 16;
  std::atomic<bool> stop{false};
  runner::EpisodeObservers observers;
  observers.push_back(std::make_unique<BagRecorder>(dir / "sessions", settings));
  auto interrupter = std::make_unique<Interrupter>();
  interrupter->ticks = 80;
  interrupter->copy_from = dir / "sessions" / "tiny-0000" / "freeplay.bag.active";
  interrupter->copy_to = dir / "killed.bag";
  observers.push_back(std::move(interrupter));
  runner::run_episode({.scenario = scenario, .seed = 7, .models = models(), .stop = stop, .id = "tiny-0000"},
                      runner::observed_by(observers));
  // The copy is what a killed process leaves: no index. Our reader says to reindex.
  try {
    read_session(dir / "killed.bag");
    ADD_FAILURE() << "an unindexed bag must be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("rosbag reindex"), std::string::npos) << e.what();
  }
  if (std::system("command -v rosbag >/dev/null 2>&1") != 0) GTEST_SKIP() << "the rosbag tool is not installed";
  ASSERT_EQ(std::system(fmt::format("cd {} && rosbag reindex killed.bag >/dev/null 2>&1", dir.string()).c_str()), 0);
  const auto rec = read_session(dir / "killed.bag");
  EXPECT_GT(rec.topic_counts.at("/tf"), 50U);  // everything up to the last complete chunk
}

TEST(BagRecorder, UnwritableFolderIsAClearErrorBeforeTheEpisode) {
  const auto dir = fresh_dir("unwritable");
  std::ofstream(dir / "blocker") << "a file, not a folder";
  BagRecorder recorder(dir / "blocker" / "sessions");
  const auto scenario = tiny("child-robot");
  try {
    recorder.begin({&scenario, "tiny-0000", 7});
    FAIL() << "begin must refuse an unwritable folder";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("session folder"), std::string::npos) << e.what();
  }
}

TEST(CameraTopics, RealNamesAndAClearErrorForOthers) {
  EXPECT_EQ(camera_topics("camera_yellow").depth_image, "camera_yellow/depth/image_raw/compressedDepth");
  EXPECT_EQ(camera_topics("env_camera").rgb_image, "env_camera/qhd/image_color/compressed");
  EXPECT_EQ(camera_topics("env_camera").rgb_info, "env_camera/qhd/camera_info");
  EXPECT_EQ(camera_topics("CameraTop").rgb_image, "/naoqi_driver/camera/front/image_raw/compressed");
  EXPECT_THROW(camera_topics("camera_green"), InputError);
}

TEST(RecordSchema, AcceptsTrueAndAMapAndRefusesBadValues) {
  EXPECT_TRUE(tiny("child-robot").record);
  const auto mapped = scenario::scenario_from_document(
      parse_yaml("name: t\ncondition: child-robot\nrecord: {jpeg_quality: 75, compression: lz4}\n", "t.yaml"));
  EXPECT_TRUE(mapped.record);
  EXPECT_EQ(mapped.recording.jpeg_quality, 75);
  EXPECT_EQ(mapped.recording.compression, "lz4");
  EXPECT_EQ(mapped.recording.png_level, 3);
  const auto off = scenario::scenario_from_document(
      parse_yaml("name: t\ncondition: child-robot\nrecord: {bag: false}\n", "t.yaml"));
  EXPECT_FALSE(off.record);
  for (const char* bad : {"record: 3", "record: {jpeg_quality: 200}", "record: {codec: x}", "record: [true]",
                          "record: {compression: zip}"}) {
    try {
      scenario::scenario_from_document(parse_yaml(fmt::format("name: t\ncondition: child-robot\n{}\n", bad), "t.yaml"));
      ADD_FAILURE() << bad << " must be refused";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("record"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("t.yaml:3"), std::string::npos) << e.what();
    }
  }
}

namespace {

// Writes camera frames straight to a recorder with `threads` encoder threads: purple with depth, env_camera without,
// each image repeated for three 30 Hz stamps (as the rig hands over a 10 Hz tick's image); returns the bag's path.
std::filesystem::path record_frames(const std::filesystem::path& dir, int threads) {
  RecordSettings settings;
  settings.encoder_threads = threads;
  BagRecorder recorder(dir / "sessions", settings);
  recorder.begin({nullptr, "frames-0000", 1});
  for (int tick = 1; tick <= 20; ++tick) {
    const double t = 0.1 * tick;
    const auto purple = pack("camera_purple", t, true);
    const auto env = pack("env_camera", t, false);
    for (int k = 0; k < 3; ++k) {
      auto p = purple;
      p.stamp = t + k / 30.0;
      recorder.write(p);
      auto e = env;
      e.stamp = t + k / 30.0;
      recorder.write(e);
    }
  }
  runner::EpisodeResult result;
  recorder.end(result);
  EXPECT_EQ(recorder.stats().frames, 120U);
  return recorder.paths().bag;
}

}  // namespace

TEST(BagRecorder, EncoderThreadsLeaveTheBagByteForByteTheSame) {
  const auto dir = fresh_dir("threads");
  const auto on_episode_thread = file_bytes(record_frames(dir / "0", 0));
  const auto on_three_threads = file_bytes(record_frames(dir / "3", 3));
  ASSERT_GT(on_episode_thread.size(), 10000U);
  EXPECT_TRUE(on_episode_thread == on_three_threads) << "bag bytes differ between 0 and 3 encoder threads";
  // Repeated images are stored with their own stamps and the same pixels.
  rosbag::Bag bag((dir / "3" / "sessions" / "frames-0000" / "freeplay.bag").string());
  rosbag::View colour(bag, rosbag::TopicQuery("camera_purple/rgb/image_raw/compressed"));
  std::vector<std::pair<double, std::vector<std::uint8_t>>> images;
  for (const auto& m : colour) {
    const auto image = m.instantiate<msg::CompressedImage>();
    images.emplace_back(sandtray_time(image->header.stamp), std::vector<std::uint8_t>(image->data.begin(), image->data.end()));
  }
  ASSERT_EQ(images.size(), 60U);
  EXPECT_NEAR(images[1].first - images[0].first, 1.0 / 30.0, 2 * 0.002 + 1e-6);  // the camera clock's jitter
  EXPECT_EQ(images[0].second, images[1].second);
  EXPECT_NE(images[0].second, images[3].second);  // the next tick's image
}

TEST(BagRecorder, AnImageThatFailsToEncodeIsReportedAndTheBagIsClosed) {
  for (const int threads : {0, 2}) {
    const auto dir = fresh_dir("bad-frame-" + std::to_string(threads));
    RecordSettings settings;
    settings.encoder_threads = threads;
    BagRecorder recorder(dir / "sessions", settings);
    recorder.begin({nullptr, "bad-0000", 1});
    auto frame = pack("camera_purple", 0.1, false);
    frame.rgb = cv::Mat(4, 4, CV_16UC1, cv::Scalar(7));  // not an 8-bit colour image
    EXPECT_THROW(
        {
          recorder.write(frame);
          runner::EpisodeResult result;
          recorder.end(result);
        },
        InputError)
        << threads << " encoder threads";
    recorder.abort();
    EXPECT_TRUE(std::filesystem::exists(recorder.paths().bag)) << threads << " encoder threads";
    EXPECT_FALSE(std::filesystem::exists(recorder.paths().active_bag)) << threads << " encoder threads";
  }
}

TEST(BagRecorder, EpisodesRecordInParallelThreads) {
  // Suites record one bag per worker thread; rosbag's plugin loading is not thread-safe (this crashed before the
  // recorder serialised opening and closing bags).
  const auto dir = fresh_dir("parallel");
  std::vector<std::thread> workers;
  std::atomic<int> written{0};
  for (int w = 0; w < 4; ++w) {
    workers.emplace_back([&, w] {
      for (int i = 0; i < 8; ++i) {
        BagRecorder recorder(dir / "sessions", {});
        recorder.begin({nullptr, fmt::format("w{}-{:04}", w, i), 1});
        recorder.write(pack("env_camera", 0.1, false));
        runner::EpisodeResult result;
        recorder.end(result);
        if (std::filesystem::exists(recorder.paths().bag)) ++written;
      }
    });
  }
  for (auto& worker : workers) worker.join();
  EXPECT_EQ(written.load(), 32);
  for (int w = 0; w < 4; ++w) {
    Bag bag;
    open_session_bag(dir / "sessions" / fmt::format("w{}-0007", w), bag);
    rosbag::View colour(bag.get(), rosbag::TopicQuery("env_camera/qhd/image_color/compressed"));
    EXPECT_EQ(colour.size(), 1U);
  }
}

TEST(Replay, AMetricTheBagCannotSupplyIsReportedAsDiffering) {
  const nlohmann::json recomputed = {{"duration_s", 10.0}, {"metrics", {{"zone_transitions", 2}}}};
  const nlohmann::json record = {{"duration_s", 10.0}, {"metrics", {{"zone_transitions", 2}, {"new_metric", 1.5}}}};
  const auto comparison = compare_with_record(recomputed, record);
  ASSERT_EQ(comparison.size(), 3U);
  int equal = 0;
  for (const auto& c : comparison) {
    if (c.name == "metrics.new_metric") {
      EXPECT_FALSE(c.equal);
      EXPECT_TRUE(std::isnan(c.replayed));
      EXPECT_EQ(c.recorded, 1.5);
    } else {
      equal += c.equal ? 1 : 0;
    }
  }
  EXPECT_EQ(equal, 2);
}

TEST(SessionVideos, TheSessionFolderHoldsEachCamerasRawVideo) {
  const auto& r = child_robot();
  const auto video = r.run_dir / "sessions" / "tiny-0000" / "video" / "camera_purple_raw.mkv";
  ASSERT_TRUE(std::filesystem::exists(video));
  EXPECT_FALSE(std::filesystem::exists(r.run_dir / "sessions" / "tiny-0000" / "video" / "camera_purple_raw.partial.mkv"));
  cv::VideoCapture capture(video.string(), cv::CAP_FFMPEG);
  ASSERT_TRUE(capture.isOpened());
  int frames = 0;
  cv::Mat frame;
  while (capture.read(frame)) {
    EXPECT_EQ(frame.cols, 64);
    EXPECT_EQ(frame.rows, 48);
    ++frames;
  }
  EXPECT_EQ(frames, r.frames);  // one video frame per published colour image
  EXPECT_EQ(raw_video_name("env_camera"), "camera_env_raw.mkv");
}

TEST(SessionVideos, ADiscardedSessionLeavesNoVideo) {
  const auto dir = fresh_dir("videos-discard");
  {
    SessionVideos videos(dir, {{"camera_yellow", 15.0}});
    videos.write("camera_yellow", cv::Mat(48, 64, CV_8UC3, cv::Scalar(1, 2, 3)));
    ASSERT_TRUE(std::filesystem::exists(dir / "video" / "camera_yellow_raw.partial.mkv"));
    videos.discard();
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir / "video"));
}
