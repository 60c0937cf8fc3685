#include "freeplay/recording/replay.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <set>

#include "freeplay/agents/annotations.hpp"
#include "freeplay/agents/perception.hpp"
#include "freeplay/core/error.hpp"
#include "freeplay/core/statistics.hpp"
#include "freeplay/recording/bag_check.hpp"
#include "freeplay/recording/publishers.hpp"
#include "freeplay/recording/ros_messages.hpp"
#include "freeplay/recording/session_layout.hpp"
#include "freeplay/results/episode_metrics.hpp"
#include "freeplay/results/summary.hpp"
#include "freeplay/sim/canvas.hpp"

namespace freeplay::recording {

namespace {

/// An item's position on the game's /tf at a tick; InputError when the recording lacks it.
Vec2 item_position(const SessionRecording& rec, double tick, const std::string& item) {
  const auto it = rec.item_positions.find(publication_tick(tick));
  if (it == rec.item_positions.end() || !it->second.contains(item)) {
    throw InputError(fmt::format("no /tf pose of '{}' at t = {} s", item, tick), "/tf", "a complete recording");
  }
  return it->second.at(item);
}

/// Runs `read` on the bytes of `file`; any failure they cause (rosbag, ROS deserialisation, an event's JSON, an
/// allocation a corrupt length asked for) becomes an InputError that names the file.
template <typename Read>
auto naming_the_bag(const std::filesystem::path& file, Read&& read) {
  try {
    return read();
  } catch (const InputError& e) {
    if (!e.where().file.empty()) throw;
    throw InputError(e.problem(), e.key(), e.allowed(), {file.string()});
  } catch (const std::exception& e) {
    throw InputError(fmt::format("not a readable freeplay recording: {}", e.what()), "SESSION_DIR",
                     "a ROS 1 bag written by `freeplay run --record`", {file.string()});
  }
}

cv::Mat decode_background(const std::vector<std::uint8_t>& png) {
  const cv::Mat bgr = cv::imdecode(cv::Mat(1, static_cast<int>(png.size()), CV_8UC1, const_cast<std::uint8_t*>(png.data())),
                                   cv::IMREAD_COLOR);
  if (bgr.empty()) throw InputError("a background image does not decode", topics::kBackground, "PNG");
  return bgr;
}

/// The drawing's coverage: the last background published in free play against the one published when it began.
double replay_drawing_coverage(const SessionRecording& rec, double freeplay_start, double freeplay_end) {
  const std::vector<std::uint8_t>* map = nullptr;
  const std::vector<std::uint8_t>* last = nullptr;
  for (const auto& [t, png] : rec.backgrounds) {
    if (t <= freeplay_start + 1e-9 || t > freeplay_end + 0.5 * kPublishTickS) continue;
    if (map == nullptr) map = &png;
    last = &png;
  }
  if (map == nullptr) return std::nan("");
  return sim::differing_pixel_share(decode_background(*last), decode_background(*map));
}

/// The recorded /tf and /zones at one tick, as the metrics' world.
class RecordedWorld final : public results::MetricsWorld {
 public:
  RecordedWorld(const SessionRecording& rec, double tick) : rec_(rec), tick_(tick) {}
  Vec2 item_position(const std::string& item) const override { return freeplay::recording::item_position(rec_, tick_, item); }
  std::string zone_at(const Vec2& p) const override {
    const std::vector<RecordedZone>* zones = nullptr;
    for (const auto& [t, z] : rec_.zones) {
      if (t <= tick_ + 1e-9) zones = &z;
    }
    if (zones == nullptr) return "";
    const RecordedZone* best = nullptr;
    double best_area = std::numeric_limits<double>::infinity();
    for (const auto& zone : *zones) {
      if (zone.polygon.size() >= 3 && zone.area_m2 < best_area && point_in_polygon(zone.polygon, p)) {
        best = &zone;
        best_area = zone.area_m2;
      }
    }
    return best != nullptr ? best->colour : "";
  }

 private:
  const SessionRecording& rec_;
  double tick_;
};

/// Feeds the recording's events to `metrics` as the episode loop fed them: events before free play, then each
/// free-play tick's events followed by that tick's gaze measurement, then the rest (a release in the debriefing).
void feed_events(const SessionRecording& rec, double freeplay_start, double duration,
                 results::EpisodeMetrics& metrics) {
  std::string ended_by = "cap";
  for (const auto& [tick, e] : rec.events) {
    if (const auto* ended = e.get<events::FreeplayEnded>(); ended && e.source == "protocol") ended_by = ended->ended_by;
  }
  // The loop's ticks: k = 0, 1, … while k·0.1 < cap, or up to the tick at which the children quit.
  long ticks = 0;
  if (std::isnan(duration)) {
    ticks = 0;
  } else if (ended_by == "quit") {
    ticks = std::lround(duration / kPublishTickS);
  } else {
    while (static_cast<double>(ticks) * kPublishTickS < duration) ++ticks;
  }
  std::size_t next = 0;
  auto feed_until = [&](auto before) {
    for (; next < rec.events.size() && before(rec.events[next].tick); ++next) {
      metrics.observe(rec.events[next].event, rec.events[next].tick, RecordedWorld(rec, rec.events[next].tick));
    }
  };
  feed_until([&](double tick) { return tick <= freeplay_start + 1e-9; });
  for (long k = 0; k < ticks; ++k) {
    const double tick_end = freeplay_start + static_cast<double>(k + 1) * kPublishTickS + 0.5 * kPublishTickS;
    feed_until([&](double tick) { return tick < tick_end; });
    metrics.measure_gaze();
  }
  feed_until([](double) { return true; });
}

/// Every message of the bag that replay needs, into `out`.
void read_messages(Bag& bag, SessionRecording& out) {
  rosbag::View view(bag.get());
  bool first = true;
  for (const auto& m : view) {
    const auto topic = m.getTopic();
    const double t = sandtray_time(m.getTime());
    ++out.topic_counts[topic];
    out.topic_types[topic] = m.getDataType();
    if (first) out.start_s = t;
    first = false;
    out.end_s = std::max(out.end_s, t);
    if (topic == topics::kEvents) {
      const auto text = read_message<msg::String>(m);
      const auto json = nlohmann::json::parse(std_string(text->data));
      RecordedEvent e;
      e.tick = json.at("tick").get<double>();
      e.event = Event{json.at("t").get<double>(), json.at("source").get<std::string>(),
                      json.at("type").get<std::string>(), json.value("data", nlohmann::json())};
      out.events.push_back(std::move(e));
    } else if (topic == topics::kTf) {
      const auto tf = read_message<msg::TFMessage>(m);
      for (const auto& x : tf->transforms) {
        const auto child = std_string(x.child_frame_id);
        if (child.rfind("touch", 0) == 0 || child.find('_') != std::string::npos) continue;
        if (std_string(x.header.frame_id) != "sandtray") continue;  // the Nao's links hang from base_link
        out.item_positions[publication_tick(sandtray_time(x.header.stamp))][child] = Vec2(x.transform.translation.x, x.transform.translation.y);
      }
    } else if (topic == topics::kZones) {
      const auto markers = read_message<msg::MarkerArray>(m);
      std::vector<RecordedZone> zones;
      for (const auto& marker : markers->markers) {
        if (marker.action != msg::Marker::ADD) continue;
        RecordedZone z;
        z.colour = std_string(marker.ns).substr(std::string("sandbox_zone_").size());
        for (std::size_t i = 0; i + 1 < marker.points.size(); ++i) z.polygon.emplace_back(marker.points[i].x, marker.points[i].y);
        z.area_m2 = std::abs(signed_area(z.polygon));
        zones.push_back(std::move(z));
      }
      out.zones.emplace_back(tick_time(publication_tick(t)), std::move(zones));
    } else if (topic == topics::kAnnotations) {
      out.annotations_yaml = std_string(read_message<msg::String>(m)->data);
    } else if (topic == topics::kInteractionEvents) {
      out.interaction_events.push_back(std_string(read_message<msg::String>(m)->data));
    } else if (topic == topics::kBackground) {
      const auto image = read_message<msg::CompressedImage>(m);
      out.backgrounds.emplace_back(tick_time(publication_tick(t)), std::vector<std::uint8_t>(image->data.begin(), image->data.end()));
    }
  }
}


/// recompute_metrics without the file named in its errors.
nlohmann::json recompute(const SessionRecording& rec) {
  double freeplay_start = 0.0;
  double duration = std::nan("");
  bool child_robot = false;
  std::map<std::string, int> interaction;
  for (const auto& [tick, e] : rec.events) {
    const auto* stage = e.get<events::Stage>();
    if (stage && e.source == "protocol" && stage->stage == "freeplay") freeplay_start = e.t;
    const auto* ended = e.get<events::FreeplayEnded>();
    if (ended && e.source == "protocol") duration = ended->duration_s;
    if (e.source == "robot") child_robot = true;
    if (const auto* message = e.get<events::InteractionEvent>()) ++interaction[message->message];
  }
  agents::SessionAnnotations annotations;
  if (!rec.annotations_yaml.empty()) {
    annotations = agents::parse_pinsoro_yaml(rec.annotations_yaml, rec.bag.string() + ":/freeplay/annotations");
    if (annotations.yellow) child_robot = false;
  }
  results::EpisodeMetrics metrics(child_robot);
  feed_events(rec, freeplay_start, duration, metrics);
  const double coverage = std::isnan(duration) ? std::nan("")
                                               : replay_drawing_coverage(rec, freeplay_start, freeplay_start + duration);
  nlohmann::json extra;
  extra["events"] = rec.events.size();
  extra["interaction_events"] = interaction;
  extra["bag_duration_s"] = rec.end_s - rec.start_s;
  extra["complete"] = !rec.annotations_yaml.empty();
  return {{"duration_s", duration}, {"metrics", metrics.to_json(duration, annotations, coverage)}, {"extra", extra}};
}


}  // namespace

std::filesystem::path open_session_bag(const std::filesystem::path& path, Bag& bag) {
  std::filesystem::path file = path;
  if (!std::filesystem::is_regular_file(path)) {
    const auto paths = session_paths(path);
    if (std::filesystem::exists(paths.bag)) {
      file = paths.bag;
    } else if (std::filesystem::exists(paths.active_bag)) {
      file = paths.active_bag;
    } else {
      throw InputError(fmt::format("no freeplay.bag in '{}'", path.string()), "SESSION_DIR",
                       "a session folder (<run>/sessions/<episode id>) or a .bag file");
    }
  }
  check_bag_structure(file);
  try {
    bag.open(file.string(), rosbag::bagmode::Read);
  } catch (const rosbag::BagUnindexedException&) {
    throw InputError(fmt::format("'{}' is not indexed (the recording was killed)", file.string()), "SESSION_DIR",
                     fmt::format("an indexed bag: run `rosbag reindex {}` first", file.string()));
  } catch (const std::exception& e) {
    throw InputError(fmt::format("'{}' is not a readable bag: {}", file.string(), e.what()), "SESSION_DIR",
                     "a ROS 1 bag written by `freeplay run --record`");
  }
  return file;
}

SessionRecording read_session(const std::filesystem::path& path) {
  SessionRecording out;
  Bag bag;
  out.bag = open_session_bag(path, bag);
  naming_the_bag(out.bag, [&] { read_messages(bag, out); });
  return out;
}

nlohmann::json recompute_metrics(const SessionRecording& rec) {
  return naming_the_bag(rec.bag, [&] { return recompute(rec); });
}

std::map<std::string, double> metric_values(const nlohmann::json& record) {
  return results::flatten_numbers(record.value("metrics", nlohmann::json::object()), "metrics",
                                  results::NullLeaves::as_nan);
}

std::vector<MetricComparison> compare_with_record(const nlohmann::json& recomputed, const nlohmann::json& record) {
  auto replayed = metric_values(recomputed);
  replayed["duration_s"] = recomputed.value("duration_s", std::nan(""));
  auto recorded = metric_values(record);
  if (record.contains("duration_s")) recorded["duration_s"] = record["duration_s"].get<double>();
  std::vector<MetricComparison> out;
  for (const auto& [name, value] : replayed) {
    MetricComparison c;
    c.name = name;
    c.replayed = value;
    const auto it = recorded.find(name);
    c.recorded = it != recorded.end() ? it->second : std::nan("");
    c.equal = it != recorded.end() && (c.replayed == c.recorded || (std::isnan(c.replayed) && std::isnan(c.recorded)));
    out.push_back(std::move(c));
  }
  for (const auto& [name, value] : recorded) {
    if (!replayed.contains(name)) out.push_back({name, std::nan(""), value, false});
  }
  return out;
}

}  // namespace freeplay::recording
