// The localisation hook of `freeplay serve` without a master: `robot_localising` puts the marker field on the
// simulated screen for 5 s, and the simulated NAO's node localises from its rendered camera or says it is lost.

#include <gtest/gtest.h>

#include "freeplay/core/rng.hpp"
#include "freeplay/localisation/nao_view.hpp"
#include "freeplay/ros/localisation_node.hpp"
#include "freeplay/runner/episode.hpp"
#include "freeplay/sim/sandtray.hpp"

// Mesa keeps a few small allocations of its GL contexts until exit (OSMesaMakeCurrent, EGL drivers): not ours.
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libOSMesa.so\nleak:libEGL_mesa.so\nleak:libgallium\nleak:libGLdispatch.so\nleak:libubsan.so\n";
}

namespace freeplay::ros_live {
namespace {

/// A child-robot free-play tick with the NAO in StandInit, its head pitched by `head_pitch`.
class ServedTick {
 public:
  explicit ServedTick(double head_pitch)
      : tray_(runner::SharedModels::shipped().catalogue, {}, Rng(SeedSequence(5).seed_for("sandtray"))) {
    tray_.signal(sim::Signal::StartFreeplay);
    for (const auto name : stage::kNaoJointNames) robot_.joint_names.emplace_back(name);
    const auto& q = stage::posture_angles(stage::NaoPosture::StandInit);
    robot_.positions.assign(q.begin(), q.end());
    robot_.positions[1] = head_pitch;  // HeadPitch
    children_.resize(1);
    children_[0].seat = "purple";
    children_[0].gaze_point = Eigen::Vector3d(0.3, -0.17, 0.0);
  }
  runner::EpisodeSnapshot at(double t) {
    runner::EpisodeSnapshot s;
    s.t = t;
    s.stage = "freeplay";
    s.tray = &tray_;
    s.children = children_;
    s.robot = &robot_;
    return s;
  }

 private:
  sim::Sandtray tray_;
  runner::RobotSnapshot robot_;
  std::vector<runner::ChildSnapshot> children_;
};

stage::RendererOptions osmesa() { return {stage::GlBackend::osmesa, stage::VisualPreset::fast, 640, 480}; }

/// Mean brightness of the screen texture over marker 700's top border (black while the field is shown).
double marker_border_brightness(const stage::Stage& stage) {
  const cv::Mat& screen = stage.screen_texture();
  const double px_per_m = screen.cols / 0.600;
  const cv::Rect border(static_cast<int>(0.065 * px_per_m), static_cast<int>(0.027 * px_per_m),
                        static_cast<int>(0.070 * px_per_m), static_cast<int>(0.006 * px_per_m));
  return cv::mean(screen(border))[0];
}

TEST(ServedLocalisation, MarkerFieldShowsForFiveSecondsAfterTheSignal) {
  ServedTick tick(0.5);
  ServedLocalisation node({}, osmesa());
  std::vector<ros_graph::Transform> frames;
  EXPECT_FALSE(node.on_signal("start_freeplay", 0.0));
  node.observe(tick.at(0.0), frames);
  EXPECT_FALSE(node.markers_on_screen());
  EXPECT_EQ(node.stage(), nullptr);  // nothing is built before the first signal
  EXPECT_TRUE(node.on_signal(kLocalisingSignal, 1.0));
  double shown_from = -1, hidden_at = -1;
  for (int k = 10; k <= 70; ++k) {
    const double t = 0.1 * k;
    node.observe(tick.at(t), frames);
    if (node.markers_on_screen() && shown_from < 0) shown_from = t;
    if (!node.markers_on_screen() && shown_from >= 0 && hidden_at < 0) hidden_at = t;
    if (k == 30) {
      ASSERT_NE(node.stage(), nullptr);
      EXPECT_LT(marker_border_brightness(*node.stage()), 10.0);
    }
  }
  EXPECT_DOUBLE_EQ(shown_from, 1.0);
  EXPECT_NEAR(hidden_at, 6.0, 1e-9);
  EXPECT_GT(marker_border_brightness(*node.stage()), 60.0);  // the game's own picture is back
}

TEST(ServedLocalisation, LocalisesFromTheRenderedCameraAndPublishesOdomAndArmReach) {
  ServedTick tick(0.5);  // looking down at the screen
  ServedLocalisation node({}, osmesa());
  node.on_signal(kLocalisingSignal, 1.0);
  std::vector<ros_graph::Transform> frames;
  const auto speech = node.observe(tick.at(1.1), frames);
  EXPECT_EQ(speech, std::vector<std::string>{"I know where I am now!"});
  ASSERT_EQ(frames.size(), 2U);
  EXPECT_EQ(frames[0].parent, "odom");
  EXPECT_EQ(frames[0].child, "sandtray");
  EXPECT_EQ(frames[1].parent, "sandtray");
  EXPECT_EQ(frames[1].child, "arm_reach");
  EXPECT_TRUE(node.publishes_arm_reach());
  const auto truth = localisation::sandtray_T_odom(node.stage()->model()).inverse();
  const Eigen::Vector3d t(frames[0].translation[0], frames[0].translation[1], frames[0].translation[2]);
  EXPECT_LT((t - truth.translation()).norm(), 0.01);
  // Held and re-published at every tick.
  std::vector<ros_graph::Transform> later;
  EXPECT_TRUE(node.observe(tick.at(1.2), later).empty());
  ASSERT_FALSE(later.empty());
  EXPECT_EQ(later[0].translation, frames[0].translation);
  EXPECT_EQ(later[0].rotation, frames[0].rotation);
}

TEST(ServedLocalisation, HeadLevelTheRobotIsLostAfterFiveSeconds) {
  ServedTick tick(0.0);  // StandInit, head level: the screen is below the top camera's view
  ServedLocalisation node({}, osmesa());
  node.on_signal(kLocalisingSignal, 1.0);
  std::vector<std::string> said;
  std::vector<ros_graph::Transform> frames;
  for (int k = 11; k <= 61; ++k) {
    for (auto& line : node.observe(tick.at(0.1 * k), frames)) said.push_back(line);
  }
  EXPECT_EQ(said, std::vector<std::string>{"I am lost!"});
  EXPECT_TRUE(frames.empty());
  EXPECT_FALSE(node.localiser().odom_T_sandtray().has_value());
  EXPECT_FALSE(node.publishes_arm_reach());
}

}  // namespace
}  // namespace freeplay::ros_live
