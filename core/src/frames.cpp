#include "freeplay/core/frames.hpp"

namespace freeplay {

void FrameTree::set(const std::string& name, const std::string& parent, const Eigen::Isometry3d& parent_T_frame,
                    double stamp) {
  frames_[name] = Frame{name, parent, parent_T_frame, stamp};
}

void FrameTree::remove(const std::string& name) {
  frames_.erase(name);
  std::vector<std::string> orphans;
  for (const auto& [child, frame] : frames_) {
    if (frame.parent == name) orphans.push_back(child);
  }
  for (const auto& child : orphans) remove(child);
}

const Frame* FrameTree::find(const std::string& name) const {
  const auto it = frames_.find(name);
  return it == frames_.end() ? nullptr : &it->second;
}

std::optional<Eigen::Isometry3d> FrameTree::root_T(const std::string& name, std::string& root) const {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  std::string current = name;
  for (std::size_t depth = 0; depth <= frames_.size(); ++depth) {
    const auto it = frames_.find(current);
    if (it == frames_.end()) {
      // An unknown name is accepted as an implicit root (e.g. "sandtray" before any frame is published).
      root = current;
      return t;
    }
    t = it->second.parent_T_frame * t;
    if (it->second.parent.empty()) {
      root = current;
      return t;
    }
    current = it->second.parent;
  }
  return std::nullopt;  // cycle
}

std::optional<Eigen::Isometry3d> FrameTree::lookup(const std::string& target, const std::string& source) const {
  std::string root_target;
  std::string root_source;
  const auto rt = root_T(target, root_target);
  const auto rs = root_T(source, root_source);
  if (!rt || !rs || root_target != root_source) return std::nullopt;
  return rt->inverse() * *rs;
}

std::vector<Frame> FrameTree::all() const {
  std::vector<Frame> out;
  out.reserve(frames_.size());
  for (const auto& [name, frame] : frames_) out.push_back(frame);
  return out;
}

}  // namespace freeplay
