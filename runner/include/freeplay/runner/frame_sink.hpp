#pragma once
// Where rendered camera frames of an episode go (video files, ROS bags): the camera rig renders each scenario
// camera at its rate and hands every frame, in simulated-time order, to its sinks.

#include <string>

#include "freeplay/stage/renderer.hpp"

namespace freeplay::runner {

/// Receives the camera frames of one episode.
class FrameSink {
 public:
  virtual ~FrameSink() = default;
  /// One rendered frame (RGB and, when the camera asks for it, metric depth), stamped with the sandtray clock.
  virtual void write(const stage::FramePack& frame) = 0;
  /// The GL renderer that drew the frames (`glGetString(GL_RENDERER)`), told once before the first frame.
  virtual void set_gl_renderer(const std::string& renderer) { (void)renderer; }
};

}  // namespace freeplay::runner
