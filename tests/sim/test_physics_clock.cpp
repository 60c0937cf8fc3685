// Box2D's step profiler reads no wall clock in freeplay's executables (sim/src/physics_clock.cpp).

#include <box2d/box2d.h>
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

namespace {

// Sleeps inside every step's contact update, so that a step takes at least a millisecond of wall time.
class SlowContacts final : public b2ContactListener {
 public:
  void PreSolve(b2Contact* /*contact*/, const b2Manifold* /*old_manifold*/) override {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    ++calls;
  }
  int calls = 0;
};

// A box resting on the ground: Box2D's own calls to its profiler's timer bind to freeplay's, which has no clock,
// so every phase of the profile reads zero although each step took over a millisecond.
TEST(PhysicsClock, BoxTwoDsStepProfileReadsNoClock) {
  b2World world(b2Vec2(0.0F, -9.8F));
  SlowContacts listener;
  world.SetContactListener(&listener);
  b2BodyDef ground_def;
  b2Body* ground = world.CreateBody(&ground_def);
  b2PolygonShape ground_box;
  ground_box.SetAsBox(1.0F, 0.1F);
  ground->CreateFixture(&ground_box, 0.0F);
  b2BodyDef body_def;
  body_def.type = b2_dynamicBody;
  body_def.position.Set(0.0F, 0.2F);
  b2Body* body = world.CreateBody(&body_def);
  b2PolygonShape box;
  box.SetAsBox(0.1F, 0.1F);
  body->CreateFixture(&box, 1.0F);
  for (int i = 0; i < 10; ++i) world.Step(1.0F / 60.0F, 8, 3);
  ASSERT_GT(listener.calls, 0);  // the steps did touch the ground (and sleep)
  const b2Profile& profile = world.GetProfile();
  EXPECT_EQ(profile.step, 0.0F);
  EXPECT_EQ(profile.collide, 0.0F);
  EXPECT_EQ(profile.solve, 0.0F);
}

TEST(PhysicsClock, TimerReadsZeroAfterTimePasses) {
  const b2Timer timer;
  std::this_thread::sleep_for(std::chrono::milliseconds(2));
  EXPECT_EQ(timer.GetMilliseconds(), 0.0F);
}

}  // namespace
