#include "freeplay/runner/perception_model.hpp"

#include <algorithm>

namespace freeplay::runner {

PerceptionModel::PerceptionModel(PerceptionSettings settings, Rng rng) : settings_(settings), rng_(rng) {}

policies::PerceivedChild PerceptionModel::sense(const ChildTruth& truth) {
  policies::PerceivedChild p;
  p.seat = truth.seat;
  p.seconds_since_touch = truth.seconds_since_touch;  // touch frames are exact (TF of the game)
  p.moving_item = truth.moving_item;
  p.speaking = truth.speaking;                         // voice activity detection on the camera microphone
  p.face_detected = rng_.bernoulli(settings_.face_detection_rate);
  if (!p.face_detected) {
    p.gaze = policies::PerceivedGaze::Unknown;
    return p;
  }
  switch (truth.gaze) {
    case agents::GazeKind::PartnerFace:
    case agents::GazeKind::Robot: p.gaze = policies::PerceivedGaze::Robot; break;
    case agents::GazeKind::Item:
    case agents::GazeKind::Tray: p.gaze = policies::PerceivedGaze::Screen; break;
    case agents::GazeKind::Away:
    case agents::GazeKind::Experimenter: p.gaze = policies::PerceivedGaze::Away; break;
  }
  const double confusion = std::clamp(settings_.gaze_noise_deg / 90.0, 0.0, 1.0);
  if (rng_.bernoulli(confusion)) {
    static constexpr policies::PerceivedGaze kClasses[] = {policies::PerceivedGaze::Robot, policies::PerceivedGaze::Screen,
                                                            policies::PerceivedGaze::Away};
    p.gaze = kClasses[rng_.uniform_int(0, 2)];
  }
  if (p.gaze == policies::PerceivedGaze::Screen) {
    const double sd = 0.002 * settings_.gaze_noise_deg;  // ≈ 1 cm per 5° at the table distance
    p.gaze_on_screen = truth.gaze_point + Vec2(rng_.normal(0, sd), rng_.normal(0, sd));
  }
  p.addressing_robot = truth.speaking && (truth.speech_to_partner || p.gaze == policies::PerceivedGaze::Robot);
  return p;
}

policies::PerceivedChild PerceptionModel::perceive(const ChildTruth& truth, double t) {
  pipeline_.emplace_back(t + settings_.latency_s, sense(truth));
  policies::PerceivedChild out;
  out.seat = truth.seat;
  bool have = false;
  while (!pipeline_.empty() && pipeline_.front().first <= t + 1e-9) {
    out = pipeline_.front().second;
    have = true;
    pipeline_.pop_front();
  }
  if (!have) {
    out.face_detected = false;  // nothing has come through the pipeline yet
    out.gaze = policies::PerceivedGaze::Unknown;
  } else {
    latest_ = out;
  }
  return have ? out : latest_.value_or(out);
}

}  // namespace freeplay::runner
