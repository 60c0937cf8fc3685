#pragma once
// A small named-frame tree (the simulated equivalent of the real system's TF tree).

#include <Eigen/Geometry>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace freeplay {

/// One named frame: its parent and the transform parent_T_frame, stamped with simulated time.
struct Frame {
  std::string name;                                      ///< e.g. "zebra", "touch1", "camera_purple_link"
  std::string parent;                                    ///< empty for a root (e.g. "sandtray")
  Eigen::Isometry3d parent_T_frame = Eigen::Isometry3d::Identity();  ///< pose of the frame in its parent
  double stamp = 0.0;                                    ///< simulated seconds
};

/// A tree of named frames; lookups compose transforms through the common ancestor.
class FrameTree {
 public:
  /// Adds or replaces frame `name` under `parent` (empty parent = a root).
  void set(const std::string& name, const std::string& parent, const Eigen::Isometry3d& parent_T_frame,
           double stamp);
  /// Removes a frame (e.g. `touch3` when that finger lifts); children become dangling and are removed too.
  void remove(const std::string& name);
  /// True when the frame exists.
  bool has(const std::string& name) const { return frames_.count(name) != 0; }
  /// The stored entry of a frame, if any.
  const Frame* find(const std::string& name) const;
  /// target_T_source: maps coordinates in `source` to coordinates in `target`; nullopt if not connected.
  std::optional<Eigen::Isometry3d> lookup(const std::string& target, const std::string& source) const;
  /// Every frame, sorted by name (deterministic order).
  std::vector<Frame> all() const;
  /// Number of frames.
  std::size_t size() const { return frames_.size(); }

 private:
  std::optional<Eigen::Isometry3d> root_T(const std::string& name, std::string& root) const;
  std::map<std::string, Frame> frames_;
};

}  // namespace freeplay
