#pragma once
// The collated PInSoRo table `pinsoro-<id>.csv` (dataset tools/collate_full_dataset; free-play-sandbox.md §4.3):
// 449 columns in the real order, one row per 30 Hz video frame of free play, built from the episode's ground truth.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "freeplay/agents/annotations.hpp"
#include "freeplay/agents/condition.hpp"
#include "freeplay/recording/poses.hpp"
#include "freeplay/runner/episode_observer.hpp"

namespace freeplay::recording {

/// The 449 column names of `pinsoro-<id>.csv`, in the real order.
const std::vector<std::string>& pinsoro_csv_columns();

/// The session-wide fields of the table.
struct PinsoroSessionInfo {
  std::string id;                      ///< session id (the `id` column)
  agents::Condition condition = agents::Condition::ChildChild;  ///< written in PInSoRo's spelling (pinsoro_name)
  std::string annotators;              ///< '+'-joined annotator names
  bool complete = true;                ///< the session was recorded to its end
  int purple_age = 0;                  ///< years
  std::string purple_gender;           ///< "male" | "female"
  int yellow_age = 0;                  ///< years (child-child only)
  std::string yellow_gender;           ///< empty in child-robot sessions
};

/// Collects the ground truth of free play tick by tick and writes the table at the end (labels need the whole
/// annotation). Columns the simulation cannot supply honestly (action units, optical flow, audio features) stay
/// empty; docs/dataset.md lists them. Face and skeleton points outside the child's camera image are empty.
class PinsoroCsv {
 public:
  /// Records the state of a free-play tick: three 30 Hz rows (the frames since the previous tick) share it;
  /// `own` holds each child's keypoints in its own camera, normalised to [0, 1] (purple, yellow).
  void observe(const runner::EpisodeSnapshot& snapshot,
               const std::array<std::optional<ProjectedKeypoints>, 2>& own = {});
  /// The CSV text (header + rows); labels come from `annotations` (times: s since free play started).
  std::string text(const PinsoroSessionInfo& info, const agents::SessionAnnotations& annotations) const;
  /// Number of rows collected so far.
  std::size_t rows() const { return rows_.size(); }

 private:
  struct ChildRow {
    bool present = false;
    Eigen::Vector3d head = Eigen::Vector3d::Zero();  // table-centre frame (m)
    Eigen::Vector3d gaze = Eigen::Vector3d::Zero();  // unit vector, table-centre frame
    // Face (70) then skeleton (18) points in the child's own camera, normalised; NaN where not in the image.
    std::optional<std::array<Eigen::Vector2f, stage::kFacePoints + stage::kCocoPoints>> keypoints;
  };
  struct Row {
    double t = 0.0;  // s since free play started
    ChildRow purple, yellow;
  };
  std::vector<Row> rows_;
};

}  // namespace freeplay::recording
