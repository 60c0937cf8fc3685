#include "freeplay/recording/poses.hpp"

#include <fmt/format.h>

#include "freeplay/core/error.hpp"
#include "freeplay/recording/camera_topics.hpp"
#include "freeplay/recording/publishers.hpp"
#include "freeplay/recording/ros_messages.hpp"

namespace freeplay::recording {

namespace {

constexpr std::array<const char*, 3> kPoseCameras = {"camera_purple", "camera_yellow", "env_camera"};

template <std::size_t N>
void append_points(std::string& out, const std::array<ImagePoint, N>& points) {
  out += '[';
  for (std::size_t i = 0; i < N; ++i) {
    const auto& p = points[i];
    out += fmt::format("{}[{:.1f},{:.1f},{:.0f}]", i == 0 ? "" : ",", p.x, p.y, p.c);
  }
  out += ']';
}

ImagePoint normalised(ImagePoint p, const stage::CameraIntrinsics& K) {
  p.x /= K.width;
  p.y /= K.height;
  return p;
}

}  // namespace

ImagePoint project(const Eigen::Vector3d& p, const stage::CameraIntrinsics& K, const Eigen::Isometry3d& sandtray_T_optical) {
  const Eigen::Vector3d q = sandtray_T_optical.inverse() * p;
  if (q.z() <= 1e-3) return {};
  const double u = K.fx * q.x() / q.z() + K.cx;
  const double v = K.fy * q.y() / q.z() + K.cy;
  if (u < 0.0 || v < 0.0 || u > K.width - 1.0 || v > K.height - 1.0) return {};
  return {u, v, 1.0};
}

ProjectedKeypoints project(const stage::AvatarKeypoints& k, const stage::CameraIntrinsics& K,
                           const Eigen::Isometry3d& sandtray_T_optical) {
  ProjectedKeypoints out;
  for (std::size_t i = 0; i < k.body.size(); ++i) out.body[i] = project(k.body[i], K, sandtray_T_optical);
  for (std::size_t i = 0; i < k.face.size(); ++i) out.face[i] = project(k.face[i], K, sandtray_T_optical);
  for (std::size_t h = 0; h < 2; ++h) {
    for (std::size_t i = 0; i < k.hands[h].size(); ++i) out.hands[h][i] = project(k.hands[h][i], K, sandtray_T_optical);
  }
  return out;
}

PoseRecorder::PoseRecorder(std::filesystem::path session_dir) : dir_(std::move(session_dir)) {}

PoseRecorder::~PoseRecorder() = default;

std::array<std::optional<ProjectedKeypoints>, 2> PoseRecorder::observe(const runner::EpisodeSnapshot& s) {
  std::array<std::optional<ProjectedKeypoints>, 2> own;
  if (s.stage != "freeplay") return own;
  if (!mirror_) {
    mirror_ = std::make_unique<runner::StageMirror>(stage::StageModel::create(runner::stage_config_for(s)));
    for (const char* name : kPoseCameras) {
      Camera c;
      c.name = name;
      c.topic = camera_topics(name).rgb_image;
      c.part = dir_ / fmt::format("freeplay.poses.{}.part", name);
      c.out.open(c.part, std::ios::binary | std::ios::trunc);
      if (!c.out) throw InputError(fmt::format("cannot write '{}'", c.part.string()), "record");
      cameras_.push_back(std::move(c));
    }
  }
  mirror_->pose(s, false, false);
  const auto& stage = mirror_->stage();
  std::array<std::optional<stage::AvatarKeypoints>, 2> keypoints;
  for (const auto role : {stage::ChildRole::purple, stage::ChildRole::yellow}) {
    if (stage.model().avatar(role).present) keypoints[static_cast<std::size_t>(role)] = stage::avatar_keypoints(stage, role);
  }
  for (auto& camera : cameras_) {
    const auto& K = stage.model().camera(camera.name).color;
    const auto pose = stage.camera_pose(camera.name);
    std::string people, faces, hands;
    for (std::size_t i = 0; i < 2; ++i) {
      if (!keypoints[i]) continue;
      const auto projected = project(*keypoints[i], K, pose);
      const std::string id = std::to_string(i + 1);
      const char* sep = people.empty() ? "" : ",";
      people += fmt::format("{}\"{}\":", sep, id);
      append_points(people, projected.body);
      faces += fmt::format("{}\"{}\":", sep, id);
      append_points(faces, projected.face);
      hands += fmt::format("{}\"{}\":{{\"left\":", sep, id);
      append_points(hands, projected.hands[1]);
      hands += ",\"right\":";
      append_points(hands, projected.hands[0]);
      hands += '}';
      if (camera.name == (i == 0 ? "camera_purple" : "camera_yellow")) {
        ProjectedKeypoints n = projected;
        for (auto& p : n.body) p = normalised(p, K);
        for (auto& p : n.face) p = normalised(p, K);
        own[i] = n;
      }
    }
    const std::string frame = fmt::format("\"poses\":{{{}}},\"faces\":{{{}}},\"hands\":{{{}}}}}", people, faces, hands);
    for (int k = kVideoFramesPerTick - 1; k >= 0; --k) {  // the frames since the previous tick show this tick's pose
      const double t = s.t - k * kVideoFrameS;
      if (s.freeplay_t - k * kVideoFrameS < -1e-9) continue;
      camera.out << (camera.first ? "" : ",") << fmt::format("{{\"ts\":{:.6f},", ros_time(t).toSec()) << frame;
      camera.first = false;
    }
  }
  return own;
}

std::optional<std::filesystem::path> PoseRecorder::finish() {
  if (cameras_.empty()) return std::nullopt;
  const auto path = dir_ / "freeplay.poses.json";
  auto tmp = path;
  tmp += ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << '{';
    for (std::size_t i = 0; i < cameras_.size(); ++i) {
      auto& c = cameras_[i];
      c.out.close();
      out << (i == 0 ? "" : ",") << fmt::format("\"{}\":{{\"frames\":[", c.topic);
      if (std::filesystem::file_size(c.part) > 0) {
        std::ifstream in(c.part, std::ios::binary);
        out << in.rdbuf();
      }
      out << "]}";
    }
    out << "}\n";
    if (!out) throw InputError(fmt::format("cannot write '{}'", path.string()), "record");
  }
  std::filesystem::rename(tmp, path);
  discard();
  return path;
}

void PoseRecorder::discard() {
  std::error_code error;
  for (auto& c : cameras_) {
    if (c.out.is_open()) c.out.close();
    std::filesystem::remove(c.part, error);
  }
}

}  // namespace freeplay::recording
