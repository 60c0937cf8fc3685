#pragma once
// What a recorded session holds, by name: the files of its folder and the topics of its bag (the tick's real topics,
// which TickTopics sends, and the recorder's own). Names only, so that reading a session back (replay, the bag
// reader, fuzz_bag) needs neither the runner nor the simulation. The camera topics are camera_topics()'.

#include <filesystem>

namespace freeplay::recording {

/// Files of one recorded session (`<run>/sessions/<episode id>/`).
struct SessionPaths {
  std::filesystem::path dir;          ///< the session folder
  std::filesystem::path bag;          ///< `freeplay.bag` (complete recordings)
  std::filesystem::path active_bag;   ///< `freeplay.bag.active` while recording (left behind by a kill)
  std::filesystem::path experiment;   ///< `experiment.yaml` (PInSoRo metadata)
  std::filesystem::path annotations;  ///< `freeplay.annotations.freeplay-sim.yaml` (ground truth, bag time base)
  std::filesystem::path bag_yaml;     ///< `freeplay.bag.yaml` (rosbag info --yaml of the closed bag)
};
/// The files of the session folder `dir`.
inline SessionPaths session_paths(const std::filesystem::path& dir) {
  return {dir, dir / "freeplay.bag", dir / "freeplay.bag.active", dir / "experiment.yaml",
          dir / "freeplay.annotations.freeplay-sim.yaml", dir / "freeplay.bag.yaml"};
}

/// The topics of a recorded bag and of the live graph: the tick's real topics, then the recorder's own.
namespace topics {
// The tick's real topics (TickTopics).
inline constexpr const char* kTf = "/tf";                                           ///< tf2_msgs/TFMessage
inline constexpr const char* kFootprints = "/footprints";                           ///< MarkerArray, latched
inline constexpr const char* kZones = "/zones";                                     ///< MarkerArray, latched
inline constexpr const char* kBackground = "/sandtray/background/image/compressed";  ///< CompressedImage (PNG), latched
inline constexpr const char* kBackgroundRaw = "/sandtray/background/image";          ///< sensor_msgs/Image rgba8, latched
inline constexpr const char* kBackgroundInfo = "/sandtray/background/camera_info";   ///< CameraInfo, latched
inline constexpr const char* kPoses = "/poses";                                     ///< PoseStamped
inline constexpr const char* kTrajectory = "/visualization_markers";                ///< Marker: the move's trajectory
inline constexpr const char* kJointStates = "/joint_states";                        ///< sensor_msgs/JointState
inline constexpr const char* kMap = "/map";                                         ///< nav_msgs/OccupancyGrid
inline constexpr const char* kInteractionEvents = "/sandtray/interaction_events";   ///< std_msgs/String
inline constexpr const char* kSpeech = "/speech";                                   ///< String: the robot's TTS text
inline constexpr const char* kSignalsPrefix = "/sandtray/signals/";                 ///< std_msgs/Empty, + the name
// The recorder's own topics (bags only).
inline constexpr const char* kAllSpeech = "/freeplay/speech";                       ///< String: JSON, everyone's
inline constexpr const char* kEvents = "/freeplay/events";                          ///< String: JSON, the event log
inline constexpr const char* kAnnotations = "/freeplay/annotations";                ///< String: PInSoRo YAML
inline constexpr const char* kScenario = "/freeplay/scenario";  ///< String, latched: the validated scenario YAML
inline constexpr const char* kEpisode = "/freeplay/episode";    ///< String, latched: JSON {id, seed, scenario}
}  // namespace topics

}  // namespace freeplay::recording
