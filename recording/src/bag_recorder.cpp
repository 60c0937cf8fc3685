#include "freeplay/recording/bag_recorder.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <deque>
#include <exception>
#include <functional>
#include <future>
#include <map>
#include <mutex>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <yaml-cpp/yaml.h>

#include "freeplay/agents/annotations.hpp"
#include "freeplay/core/atomic_file.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/core/task_pool.hpp"
#include "freeplay/recording/audio.hpp"
#include "freeplay/recording/audio_voice.hpp"
#include "freeplay/recording/audio_data.hpp"
#include "freeplay/recording/bag_description.hpp"
#include "freeplay/recording/camera_topics.hpp"
#include "freeplay/recording/pinsoro_csv.hpp"
#include "freeplay/recording/poses.hpp"
#include "freeplay/recording/publishers.hpp"
#include "freeplay/recording/ros_messages.hpp"
#include "freeplay/recording/session_files.hpp"
#include "freeplay/recording/session_videos.hpp"
#include "freeplay/recording/tick_topics.hpp"
#include "message_builders.hpp"
#include "freeplay/sim/sandtray.hpp"

namespace freeplay::recording {

namespace {

using detail::kCameraLinks;
using detail::StaticLink;
using detail::transform;

constexpr double kCameraMaxPhaseS = 0.012;  // a 30 Hz camera's publishing phase stays well inside its 33 ms period
// Voices of the adults (docs/recording.md, Audio): pitch, articulation rate and where they speak from.
constexpr double kRobotPitchHz = 200.0;
constexpr double kExperimenterPitchHz = 210.0;
constexpr double kAdultSyllablesPerS = 4.0;
const Eigen::Vector3d kRobotMouth(0.3, 0.15, 0.40);         // the NAO's head, standing on the yellow side
const Eigen::Vector3d kExperimenterMouth(-0.8, -0.17, 0.9);  // standing beside the table

rosbag::compression::CompressionType compression_of(const std::string& name) {
  if (name == "lz4") return rosbag::compression::LZ4;
  if (name == "bz2") return rosbag::compression::BZ2;
  return rosbag::compression::Uncompressed;
}

/// One frame's compressed images (empty when the frame has no such image).
struct EncodedImages {
  std::vector<std::uint8_t> jpeg;   ///< colour, JPEG
  std::vector<std::uint8_t> depth;  ///< compressedDepth payload
};

EncodedImages encode_images(const cv::Mat& rgb, const cv::Mat& depth_m, const RecordSettings& settings) {
  EncodedImages out;
  if (!rgb.empty()) out.jpeg = encode_jpeg(rgb, settings.jpeg_quality);
  if (!depth_m.empty()) out.depth = encode_compressed_depth(depth_m, settings.png_level);
  return out;
}

}  // namespace

struct BagRecorder::Impl {
  std::filesystem::path root;
  RecordSettings settings;
  SessionPaths paths;
  std::string id;
  scenario::Condition condition = scenario::Condition::ChildChild;
  std::uint64_t seed = 0;
  std::string scenario_name;
  std::string gl_renderer;
  Bag bag;
  bool open = false;
  std::mutex mutex;
  RecordingStats stats;
  std::unique_ptr<TickTopics> tick_topics;  // the tick's real topics (made at begin)
  std::optional<double> freeplay_start;
  PinsoroCsv csv;           // the collated 30 Hz table of free play
  std::unique_ptr<PoseRecorder> poses;  // freeplay.poses.json
  std::unique_ptr<SessionVideos> videos;  // video/camera_*_raw.mkv (when cameras render)
  std::vector<std::pair<std::string, std::unique_ptr<MicrophoneStream>>> microphones;  // topic → SR300 microphone
  std::unique_ptr<Voice> voice;  // record.voice
  std::uint64_t utterances = 0;
  PublisherClocks clocks;  // every real publisher's phase and jitter (seeded by the episode)
  std::map<double, std::string> markers;
  std::map<std::string, std::string> notes;
  std::vector<Participant> participants;  // from the first snapshot (profiles complete at the end)
  std::map<std::string, double> camera_tf_t;

  // Camera images are compressed on the encoder threads; every bag write waits its turn in `pending`, so the bag
  // holds the messages in the order they were put, whatever the number of threads.
  struct Pending {
    std::shared_future<std::shared_ptr<const EncodedImages>> images;  // valid for a camera frame
    std::function<void(const EncodedImages*)> write;                  // the bag writes, run in order
  };
  std::unique_ptr<TaskPool> encoders;
  std::deque<Pending> pending;
  struct LastEncoded {  // a camera's last images: faster-than-tick cameras repeat them, encoded once
    cv::Mat rgb, depth_m;
    std::shared_future<std::shared_ptr<const EncodedImages>> images;
  };
  std::map<std::string, LastEncoded> last_encoded;

  /// Bag writes that are due: every one whose images are ready, or all of them with `wait`.
  void flush(bool wait) {
    while (!pending.empty()) {
      auto& head = pending.front();
      std::shared_ptr<const EncodedImages> images;
      if (head.images.valid()) {
        if (!wait && head.images.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return;
        images = head.images.get();  // rethrows an encoder's exception
      }
      auto write = std::move(head.write);
      pending.pop_front();
      write(images.get());
    }
  }

  /// The most camera frames waiting for their encoding before the episode thread waits (bounds the memory).
  std::size_t max_pending_frames() const { return 2 * static_cast<std::size_t>(std::max(1, encoders->threads())) + 2; }

  template <class M>
  void put(const char* topic, double t, const M& message, bool latched = false) {
    put(std::string(topic), t, message, latched);
  }

  /// Writes `message` now, or after the writes still pending.
  template <class M>
  void put(const std::string& topic, double t, const M& message, bool latched = false) {
    if (pending.empty()) {
      write_now(topic, t, message, latched);
    } else {
      pending.push_back({{}, [this, topic, t, message, latched](const EncodedImages*) {
                           write_now(topic, t, message, latched);
                         }});
    }
  }

  template <class M>
  void write_now(const std::string& topic, double t, const M& message, bool latched = false) {
    if (latched) {
      auto header = boost::make_shared<ros::M_string>();
      (*header)["callerid"] = "/sandtray";
      (*header)["latching"] = "1";
      (*header)["type"] = ros::message_traits::datatype<M>();
      (*header)["md5sum"] = ros::message_traits::md5sum<M>();
      (*header)["message_definition"] = ros::message_traits::definition<M>();
      bag.get().write(topic, ros_time(t), message, header);
    } else {
      bag.get().write(topic, ros_time(t), message);
    }
    ++stats.messages;
  }

  ExperimentInfo experiment(const nlohmann::json* children, bool complete) const {
    ExperimentInfo info;
    const auto start_s = static_cast<std::time_t>(ros_time(freeplay_start.value_or(0.0)).sec);
    std::tm utc{};
    gmtime_r(&start_s, &utc);
    info.header = fmt::format("{:04}-{:02}-{:02} {:02}:{:02}:{:02} UTC: synthetic session recorded by freeplay-sim: "
                              "scenario {}, episode {}, seed {}",
                              utc.tm_year + 1900, utc.tm_mon + 1, utc.tm_mday, utc.tm_hour, utc.tm_min, utc.tm_sec,
                              scenario_name, id, seed);
    info.timestamp_ns = ros_time(freeplay_start.value_or(0.0)).toNSec();
    info.condition = condition;
    const std::string suffix = condition == scenario::Condition::ChildRobot ? "2" : "1";
    for (const auto& p : participants) {
      Participant out = p;
      if (children != nullptr && children->contains(p.id)) {
        const auto& c = (*children)[p.id];
        out.age = c.value("age", p.age);
        out.gender = c.value("gender", p.gender);
        out.tablet_familiarity = c.value("tablet_familiarity", std::string("na"));
      }
      const std::string seat = p.id;
      out.id = fmt::format("{}-{}{}", id, seat == "purple" ? "p" : "y", suffix);
      (seat == "purple" ? info.purple : info.yellow) = out;
    }
    info.markers = markers;
    info.notes = notes;
    info.notes["general"] = fmt::format("freeplay-sim scenario '{}', episode {}, seed {}{}", scenario_name, id, seed,
                                        gl_renderer.empty() ? "" : "; cameras rendered by " + gl_renderer);
    if (!complete) {
      info.issues.push_back(
          "recording incomplete: the episode was interrupted (a killed process leaves freeplay.bag.active: run "
          "`rosbag reindex` on it)");
    }
    return info;
  }

  void write_csv(const nlohmann::json& children, const agents::SessionAnnotations& annotations) const {
    PinsoroSessionInfo table;
    table.id = id;
    table.condition = condition;
    table.annotators = "freeplay-sim";
    const auto info = experiment(&children, true);
    if (info.purple) std::tie(table.purple_age, table.purple_gender) = std::pair(info.purple->age, info.purple->gender);
    if (info.yellow) std::tie(table.yellow_age, table.yellow_gender) = std::pair(info.yellow->age, info.yellow->gender);
    const auto path = paths.dir / fmt::format("pinsoro-{}.csv", id);
    write_file_atomically(path, csv.text(table, annotations));
    write_md5_file(path);
  }

  void write_experiment(const nlohmann::json* children, bool complete,
                        const agents::SessionAnnotations* annotations = nullptr) const {
    auto info = experiment(children, complete);
    if (annotations != nullptr) info.social_engagement = social_engagement_likert(*annotations);
    write_file_atomically(paths.experiment, to_experiment_yaml(info));
  }

  void close_bag() {
    if (!open) return;
    open = false;
    std::exception_ptr encoding_error;  // an image that failed to encode: close what was written, then report it
    try {
      flush(true);
    } catch (...) {
      encoding_error = std::current_exception();
      pending.clear();
    }
    bag.close();
    std::filesystem::rename(paths.active_bag, paths.bag);
    if (encoding_error) std::rethrow_exception(encoding_error);
  }

  /// Writes the tick's messages in their order.
  void put_all(const std::vector<TopicMessage>& messages) {
    for (const auto& m : messages) {
      std::visit([&](const auto& payload) { put(m.topic, m.published, payload, m.latched); }, m.message);
    }
  }

  /// Every utterance of the tick becomes sound in both microphones; the MP3 frames completed so far are written.
  void write_audio(double t, const runner::EpisodeSnapshot& s, bool last = false) {
    for (const auto& e : s.new_events) {
      const auto* speech = e.source.rfind("child.", 0) == 0 ? e.get<events::ChildSpeech>() : nullptr;
      const auto* say = e.source == "robot" || e.source == "experimenter" ? e.get<events::Say>() : nullptr;
      const bool child = speech != nullptr;
      if (!child && say == nullptr) continue;
      Utterance u;
      u.start_s = e.t;
      u.duration_s = child ? speech->duration_s : say->duration_s;
      u.syllables = child ? speech->syllables
                          : std::max(1, static_cast<int>(std::lround(kAdultSyllablesPerS * u.duration_s)));
      u.seed = splitmix64(seed ^ fnv1a64(e.source) ^ ++utterances);
      u.pitch_hz = e.source == "robot" ? kRobotPitchHz : kExperimenterPitchHz;
      u.mouth = e.source == "robot" ? kRobotMouth : kExperimenterMouth;
      u.text = child ? std::string() : say->text;
      u.kind = child ? speech->kind : std::string();
      for (const auto& c : s.children) {
        if (child && "child." + c.seat == e.source) {
          u.pitch_hz = child_pitch_hz(c.age_years);
          u.mouth = c.head;
        }
      }
      const auto sound = voice->speak(u);
      for (auto& [topic, mic] : microphones) mic->add(u, sound);
    }
    for (auto& [topic, mic] : microphones) {
      for (auto& [captured, bytes] : last ? mic->finish() : mic->advance(t)) {
        msg::AudioData chunk;
        chunk.data.assign(bytes.begin(), bytes.end());
        put(topic, clocks.publish(topic, captured, kCameraMaxPhaseS), chunk);
      }
    }
  }

  void write_event(double t, const Event& e) {
    auto json = e.to_json();
    json["tick"] = t;
    msg::String text;
    text.data = ros_string(json.dump());
    put(topics::kEvents, t, text);
    ++stats.events;
    put_all(tick_topics->event(t, e));  // interaction events, the robot's speech, the stages' signals
    if (e.get<events::Say>() != nullptr || e.get<events::ChildSpeech>() != nullptr) {
      msg::String speech;
      speech.data = ros_string(nlohmann::json{{"t", e.t}, {"who", e.source}, {"data", e.data()}}.dump());
      put(topics::kAllSpeech, t, speech);
    }
    if (const auto* started = e.get<events::Stage>(); started && e.source == "protocol") {
      const auto& stage = started->stage;
      if (stage == "freeplay") freeplay_start = e.t;
      if (freeplay_start || stage == "debriefing") {
        const double since = e.t - freeplay_start.value_or(e.t);
        markers[since] = "note";
        notes[fmt::format("{:.1f}", since)] = stage + " starts";
      }
    }
  }
};

BagRecorder::BagRecorder(std::filesystem::path sessions_root, RecordSettings settings)
    : impl_(std::make_unique<Impl>()) {
  impl_->root = std::move(sessions_root);
  impl_->settings = std::move(settings);
  impl_->voice = make_voice(impl_->settings.voice);
  impl_->encoders = std::make_unique<TaskPool>(impl_->settings.encoder_threads);
}

BagRecorder::~BagRecorder() {
  try {
    if (impl_->open) abort();
  } catch (...) {  // a destructor must not throw; the bag stays reindexable
  }
}

void BagRecorder::begin(const runner::EpisodeInfo& info) {
  std::lock_guard lock(impl_->mutex);
  auto& d = *impl_;
  d.id = info.id;
  d.seed = info.seed;
  d.clocks = PublisherClocks(info.seed);
  TickTopicsOptions topics_options;
  topics_options.png_level = d.settings.png_level;
  const bool child_robot = info.scenario != nullptr && info.scenario->condition == scenario::Condition::ChildRobot;
  topics_options.streams = child_robot ? kBagStreams : kBagStreams & ~unsigned{kRobotLinks};
  if (child_robot) topics_options.arm_reach_m = info.scenario->robot.arm_reach_m;
  d.tick_topics = std::make_unique<TickTopics>(info.seed, topics_options);
  if (info.scenario != nullptr) {
    d.condition = info.scenario->condition;
    d.scenario_name = info.scenario->name;
  }
  d.paths = session_paths(d.root / info.id);
  std::error_code error;
  std::filesystem::create_directories(d.paths.dir, error);
  if (error) {
    throw InputError(fmt::format("cannot create the session folder '{}': {}", d.paths.dir.string(), error.message()),
                     "record", "a writable run folder (--out)");
  }
  for (const auto& stale : {d.paths.bag, d.paths.active_bag, d.paths.annotations, d.paths.bag_yaml}) {
    std::filesystem::remove(stale, error);
  }
  std::filesystem::remove_all(d.paths.dir / "video", error);  // an earlier, interrupted attempt's videos
  try {
    d.write_experiment(nullptr, false);
    d.bag.open(d.paths.active_bag.string(), rosbag::bagmode::Write);
  } catch (const std::exception& e) {
    throw InputError(fmt::format("cannot write the session folder '{}': {}", d.paths.dir.string(), e.what()),
                     "record", "a writable run folder (--out)");
  }
  std::filesystem::create_directories(d.paths.dir / "audio");
  for (const char* camera : {"camera_purple", "camera_yellow"}) {  // the SR300s' microphones (audio_capture)
    const auto link = std::find_if(std::begin(kCameraLinks), std::end(kCameraLinks), [&](const StaticLink& l) {
      return std::string(l.frame) == std::string(camera) + "_link";
    });
    d.microphones.emplace_back(std::string(camera) + "/audio",
                               std::make_unique<MicrophoneStream>(link->xyz, d.paths.dir / "audio" /
                                                                                 fmt::format("freeplay_{}_audio", camera),
                                                                  splitmix64(d.seed ^ fnv1a64(camera))));
  }
  std::map<std::string, double> rates_hz;
  if (info.scenario != nullptr) {
    for (const auto& camera : info.scenario->cameras) rates_hz[camera.name] = camera.rate_hz;
  }
  d.videos = std::make_unique<SessionVideos>(d.paths.dir, std::move(rates_hz));
  d.bag.get().setChunkThreshold(static_cast<std::uint32_t>(d.settings.chunk_kb) * 1024U);
  d.bag.get().setCompression(compression_of(d.settings.compression));
  d.open = true;
  if (info.scenario != nullptr) {
    msg::String scenario;
    scenario.data = ros_string(YAML::Dump(info.scenario->source));
    d.put(topics::kScenario, 0.0, scenario, true);
  }
  msg::String episode;
  episode.data = ros_string(nlohmann::json{{"id", d.id}, {"seed", d.seed}, {"scenario", d.scenario_name}}.dump());
  d.put(topics::kEpisode, 0.0, episode, true);
}

void BagRecorder::observe(const runner::EpisodeSnapshot& snapshot) {
  std::lock_guard lock(impl_->mutex);
  auto& d = *impl_;
  if (!d.open || snapshot.tray == nullptr) return;
  const double t = snapshot.t;
  if (d.participants.empty()) {
    for (const auto& c : snapshot.children) d.participants.push_back({c.seat, c.age_years, c.gender, "na"});
  }
  for (const auto& e : snapshot.new_events) d.write_event(t, e);
  d.put_all(d.tick_topics->frames(snapshot));
  if (!d.poses) d.poses = std::make_unique<PoseRecorder>(d.paths.dir);
  d.csv.observe(snapshot, d.poses->observe(snapshot));
  d.write_audio(t, snapshot);
  d.put_all(d.tick_topics->state(snapshot));
}

void BagRecorder::write(const stage::FramePack& frame) {
  std::lock_guard lock(impl_->mutex);
  auto& d = *impl_;
  if (!d.open) return;
  const auto names = camera_topics(frame.camera);
  d.videos->write(frame.camera, frame.rgb);
  // The camera driver stamps each stream when it publishes it: colour and depth each with their own phase.
  const double t = d.clocks.publish(frame.camera + "/rgb", frame.stamp, kCameraMaxPhaseS);
  const double t_depth = d.clocks.publish(frame.camera + "/depth", frame.stamp, kCameraMaxPhaseS);
  const auto stamp = ros_time(t);
  const Eigen::Quaterniond q(frame.sandtray_T_camera_optical.rotation());
  const Eigen::Vector3d xyz = frame.sandtray_T_camera_optical.translation();
  const auto last = d.camera_tf_t.find(frame.camera);
  if (last == d.camera_tf_t.end() || t - last->second >= 0.1 - 1e-9) {  // optical frames at 10 Hz
    d.camera_tf_t[frame.camera] = t;
    msg::TFMessage tf;
    tf.transforms.push_back(transform(stamp, "sandtray", names.rgb_frame, xyz, q));
    if (!frame.depth_m.empty() && names.depth_frame != names.rgb_frame) {
      tf.transforms.push_back(transform(stamp, "sandtray", names.depth_frame, xyz, q));
    }
    d.put(topics::kTf, t, tf);
  }
  if (frame.rgb.empty() && frame.depth_m.empty()) return;
  auto& cached = d.last_encoded[frame.camera];
  if (!cached.images.valid() || cached.rgb.data != frame.rgb.data || cached.depth_m.data != frame.depth_m.data) {
    // The rig hands a repeated image over with the same pixels: those are compressed once.
    cached.rgb = frame.rgb;
    cached.depth_m = frame.depth_m;
    cached.images = d.encoders
                        ->submit([rgb = frame.rgb, depth_m = frame.depth_m, settings = d.settings] {
                          return std::make_shared<const EncodedImages>(encode_images(rgb, depth_m, settings));
                        })
                        .share();
  }
  const auto K = frame.K;
  const auto K_depth = frame.K_depth.width > 0 ? frame.K_depth : frame.K;
  d.pending.push_back({cached.images, [&d, names, t, t_depth, K, K_depth](const EncodedImages* images) {
                         const auto header_stamp = ros_time(t);
                         const auto depth_stamp = ros_time(t_depth);
                         if (!images->jpeg.empty()) {
                           msg::CompressedImage image;
                           image.header.stamp = header_stamp;
                           image.header.frame_id = ros_string(names.rgb_frame);
                           image.format = ros_string(names.rgb_format);
                           image.data.assign(images->jpeg.begin(), images->jpeg.end());
                           d.write_now(names.rgb_image, t, image);
                           d.write_now(names.rgb_info, t, camera_info(K, names.rgb_frame, header_stamp));
                         }
                         if (!images->depth.empty()) {
                           msg::CompressedImage depth;
                           depth.header.stamp = depth_stamp;
                           depth.header.frame_id = ros_string(names.depth_frame);
                           depth.format = ros_string("16UC1; compressedDepth");
                           depth.data.assign(images->depth.begin(), images->depth.end());
                           d.write_now(names.depth_image, t_depth, depth);
                           d.write_now(names.depth_info, t_depth, camera_info(K_depth, names.depth_frame, depth_stamp));
                         }
                         ++d.stats.frames;
                       }});
  d.flush(false);
  std::size_t frames_waiting = 0;
  for (const auto& p : d.pending) frames_waiting += p.images.valid() ? 1 : 0;
  if (frames_waiting > d.max_pending_frames()) {
    const auto oldest = std::find_if(d.pending.begin(), d.pending.end(), [](const auto& p) { return p.images.valid(); });
    oldest->images.wait();
    d.flush(false);
  }
}

void BagRecorder::set_gl_renderer(const std::string& renderer) {
  std::lock_guard lock(impl_->mutex);
  impl_->gl_renderer = renderer;
}

void BagRecorder::end(runner::EpisodeResult& result) {
  std::lock_guard lock(impl_->mutex);
  auto& d = *impl_;
  if (!d.open) return;
  const double end_t = result.simulated_s;
  const std::string header =
      fmt::format("Synthetic ground truth by freeplay-sim: {} seed {} (times: s since free play started)", d.id, d.seed);
  msg::String annotations;
  annotations.data = ros_string(agents::to_pinsoro_yaml(result.annotations, 0.0, header));
  d.put(topics::kAnnotations, end_t, annotations, true);
  d.write_audio(end_t, runner::EpisodeSnapshot{}, true);
  d.close_bag();
  d.videos->close();
  const double base = ros_time(d.freeplay_start.value_or(0.0)).toSec();
  write_file_atomically(d.paths.annotations,
                        agents::to_pinsoro_yaml(result.annotations, base,
                                                "Annotations made by freeplay-sim (synthetic ground truth; ROS time)"));
  const auto children = result.record.is_object() ? result.record.value("children", nlohmann::json::object())
                                                  : nlohmann::json::object();
  d.write_experiment(&children, true, &result.annotations);
  write_file_atomically(d.paths.bag_yaml, describe_bag_yaml(d.paths.bag, "freeplay.bag", d.settings.compression));
  write_md5_file(d.paths.bag);
  d.write_csv(children, result.annotations);
  if (d.poses) {
    if (const auto json = d.poses->finish()) write_md5_file(*json);
  }
  result.record["recording"] = (std::filesystem::path("sessions") / d.id).generic_string();
}

void BagRecorder::abort() {
  std::lock_guard lock(impl_->mutex);
  auto& d = *impl_;
  if (!d.open) return;
  try {
    d.close_bag();
  } catch (const std::exception&) {  // the episode's own error is the one to report; the bag is closed
  }
  if (d.poses) d.poses->discard();
  d.videos->discard();
  d.write_experiment(nullptr, false);
}

const SessionPaths& BagRecorder::paths() const { return impl_->paths; }

RecordingStats BagRecorder::stats() const {
  std::lock_guard lock(impl_->mutex);
  return impl_->stats;
}

}  // namespace freeplay::recording
