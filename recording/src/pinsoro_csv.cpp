#include "freeplay/recording/pinsoro_csv.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>

#include "freeplay/recording/publishers.hpp"

namespace freeplay::recording {

namespace {

// The dataset's table-centre frame `sandtray_centre`: the sandtray origin sits at (−0.3, +0.169, 0) from it.
const Eigen::Vector3d kSandtrayInCentre(-0.3, 0.169, 0.0);
constexpr std::array<const char*, 18> kActionUnits = {"01", "02", "04", "05", "06", "07", "09", "10", "12",
                                                      "14", "15", "17", "20", "23", "25", "26", "28", "45"};
constexpr std::array<const char*, 2> kSeats = {"purple", "yellow"};

std::vector<std::string> make_columns() {
  std::vector<std::string> c = {"timestamp",          "id",
                                "condition",          "annotators",
                                "complete",           "purple_child_age",
                                "purple_child_gender", "yellow_child_age",
                                "yellow_child_gender"};
  for (const char* seat : kSeats) {
    const std::string p = fmt::format("{}_child_", seat);
    c.push_back(fmt::format("{}_frame_idx", seat));
    for (int i = 0; i < 70; ++i) {
      c.push_back(fmt::format("{}face{:02}_x", p, i));
      c.push_back(fmt::format("{}face{:02}_y", p, i));
    }
    for (int i = 0; i < 18; ++i) {
      c.push_back(fmt::format("{}skel{:02}_x", p, i));
      c.push_back(fmt::format("{}skel{:02}_y", p, i));
    }
    for (const char* k : {"x", "y", "z", "rx", "ry", "rz"}) c.push_back(p + "head_" + k);
    for (const char* k : {"x", "y", "z"}) c.push_back(p + "gaze_" + k);
    for (const char* au : kActionUnits) c.push_back(p + "au" + au);
    for (const char* k : {"intensity_avg", "intensity_stdev", "intensity_max", "direction_avg", "direction_stdev"}) {
      c.push_back(p + "motion_" + k);
    }
  }
  for (int i = 0; i < 16; ++i) c.push_back(fmt::format("audio{:02}", i));
  for (const char* seat : kSeats) {
    for (const char* axis : {"task_engagement", "social_engagement", "social_attitude"}) {
      c.push_back(fmt::format("{}_child_{}", seat, axis));
    }
  }
  return c;
}

/// The label of `axis` at time `t` of a timeline ("missingdata" when none covers it).
std::string label_at(const agents::ChildTimeline& timeline, agents::Axis axis, double t) {
  for (const auto& bout : timeline) {
    if (bout.axis == axis && bout.start <= t && t < bout.stop) return std::string(bout.name());
  }
  return "missingdata";
}

/// One child's columns from frame_idx to the motion columns.
using Points = std::array<Eigen::Vector2f, stage::kFacePoints + stage::kCocoPoints>;

/// Face then skeleton points of one child in its own camera (NaN: not in the image).
std::optional<Points> own_points(const std::optional<ProjectedKeypoints>& k) {
  if (!k) return std::nullopt;
  Points out;
  auto put = [](const ImagePoint& p) {
    return p.c > 0.0 ? Eigen::Vector2f(static_cast<float>(p.x), static_cast<float>(p.y))
                     : Eigen::Vector2f::Constant(std::nanf(""));
  };
  for (std::size_t i = 0; i < k->face.size(); ++i) out[i] = put(k->face[i]);
  for (std::size_t i = 0; i < k->body.size(); ++i) out[k->face.size() + i] = put(k->body[i]);
  return out;
}

void child_fields(std::string& line, bool present, std::size_t frame, const Eigen::Vector3d& head,
                  const Eigen::Vector3d& gaze, const std::optional<Points>& keypoints) {
  if (!present) {
    line += std::string(1 + 140 + 36 + 6 + 3 + 18 + 5, ',');
    return;
  }
  line += fmt::format(",{}", frame);
  for (std::size_t i = 0; i < std::tuple_size_v<Points>; ++i) {  // OpenPose face, then skeleton
    const bool shown = keypoints && !std::isnan((*keypoints)[i].x());
    line += shown ? fmt::format(",{:.5f},{:.5f}", (*keypoints)[i].x(), (*keypoints)[i].y()) : std::string(",,");
  }
  // Head pose: position in the table-centre frame; rotation vector of the head frame (x axis along the gaze).
  const Eigen::Vector3d x = gaze.normalized();
  const Eigen::AngleAxisd r(Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitX(), x));
  const Eigen::Vector3d rv = r.axis() * r.angle();
  line += fmt::format(",{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f}", head.x(), head.y(), head.z(), rv.x(), rv.y(), rv.z());
  line += fmt::format(",{:.4f},{:.4f},{:.4f}", x.x(), x.y(), x.z());
  line += std::string(18 + 5, ',');  // action units, optical flow: not simulated
}

}  // namespace

const std::vector<std::string>& pinsoro_csv_columns() {
  static const std::vector<std::string> columns = make_columns();
  return columns;
}

void PinsoroCsv::observe(const runner::EpisodeSnapshot& s, const std::array<std::optional<ProjectedKeypoints>, 2>& own) {
  if (s.stage != "freeplay") return;
  Row row;
  row.purple.keypoints = own_points(own[0]);
  row.yellow.keypoints = own_points(own[1]);
  for (const auto& child : s.children) {
    auto& out = child.seat == "purple" ? row.purple : row.yellow;
    out.present = true;
    out.head = child.head + kSandtrayInCentre;
    const Eigen::Vector3d direction = child.gaze_point - child.head;
    out.gaze = direction.norm() > 1e-9 ? direction.normalized() : Eigen::Vector3d::UnitX();
  }
  // The frames since the previous tick show this tick's state.
  for (int k = kVideoFramesPerTick - 1; k >= 0; --k) {
    row.t = s.freeplay_t - k * kVideoFrameS;
    if (row.t < -1e-9) continue;
    rows_.push_back(row);
  }
}

std::string PinsoroCsv::text(const PinsoroSessionInfo& info, const agents::SessionAnnotations& annotations) const {
  std::string out;
  const auto& columns = pinsoro_csv_columns();
  for (std::size_t i = 0; i < columns.size(); ++i) out += (i == 0 ? "" : ",") + columns[i];
  out += '\n';
  const bool yellow_child = info.condition != agents::Condition::ChildRobot;
  const std::string_view condition = agents::pinsoro_name(info.condition);
  for (std::size_t frame = 0; frame < rows_.size(); ++frame) {
    const auto& row = rows_[frame];
    std::string line = fmt::format("{:.4f},{},{},{},{},{},{},", row.t, info.id, condition, info.annotators,
                                   info.complete ? "True" : "False", info.purple_age, info.purple_gender);
    line += yellow_child ? fmt::format("{},{}", info.yellow_age, info.yellow_gender) : std::string(",");
    child_fields(line, row.purple.present, frame, row.purple.head, row.purple.gaze, row.purple.keypoints);
    child_fields(line, yellow_child && row.yellow.present, frame, row.yellow.head, row.yellow.gaze,
                 row.yellow.keypoints);
    line += std::string(16, ',');  // audio features: empty in the real table too
    for (const auto* seat : {&annotations.purple, &annotations.yellow}) {
      const bool shown = seat == &annotations.purple || yellow_child;
      for (const auto axis : agents::kAxes) {
        line += ',';
        if (shown) line += seat->has_value() ? label_at(**seat, axis, row.t) : std::string("missingdata");
      }
    }
    out += line;
    out += '\n';
  }
  return out;
}

}  // namespace freeplay::recording
