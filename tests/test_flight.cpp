// The viewer's camera near a black hole (src/viewer/flight.hpp): the free motions it can switch
// to, against closed forms written here: a circular orbit keeps its radius and moves at the
// static observers' sqrt(M / (r - 2M)), sweeping Omega = sqrt(M / r^3) of coordinate angle per
// unit of coordinate time, t = tau / sqrt(1 - 3M/r); a fall from rest at r0 moves at
// sqrt(2M (1/r - 1/r0)) / sqrt(1 - 2M/r0) (MTW eq. 31.10's energy); both start at the camera's
// event, and a boost returns to powered flight.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "support/test_support.hpp"
#include "viewer/flight.hpp"
#include "viewer/frame_rate.hpp"

namespace lightcone {
namespace {

Camera camera_at(const Vec3& position, double time) {
  Camera c;
  c.world_line.position = position;
  c.world_line.time = time;
  c.forward = normalize(Vec3{0.2, 0, -1});
  return c;
}

TEST(Flight, OrbitsThroughItsEventAtTheCircularSpeed) {
  const BlackHole hole{{1, 2, 3}, 1, std::nullopt};
  const double r = 10, t0 = 7;
  Flight flight(camera_at(hole.position + Vec3{r, 0, 0}, t0));
  ASSERT_FALSE(flight.start_orbit(hole));
  EXPECT_EQ(flight.mode, Flight::Mode::kOrbit);
  // Still at its event.
  EXPECT_LT(length(flight.camera.world_line.position - (hole.position + Vec3{r, 0, 0})), 1e-9);
  EXPECT_NEAR(flight.camera.world_line.time, t0, 1e-9);
  // Moving toward its view, at the circular speed.
  EXPECT_NEAR(flight.speed, std::sqrt(1 / (r - 2)), 1e-12);
  EXPECT_LT(flight.camera.world_line.velocity.z, 0);
  const double tau = 3;
  ASSERT_TRUE(flight.advance(tau, &hole));
  const Vec3 from_hole = flight.camera.world_line.position - hole.position;
  EXPECT_NEAR(length(from_hole), r, 1e-9);
  const double dt = tau / std::sqrt(1 - 3 / r);
  EXPECT_NEAR(flight.camera.world_line.time, t0 + dt, 1e-9);
  EXPECT_NEAR(std::acos(from_hole.x / r), std::sqrt(1 / (r * r * r)) * dt, 1e-9);
  // A boost leaves the orbit for powered flight along the view.
  flight.set_speed(0.5);
  EXPECT_EQ(flight.mode, Flight::Mode::kPowered);
  EXPECT_FALSE(flight.camera.motion.geodesic);
}

TEST(Flight, NoOrbitInsideThePhotonSphere) {
  const BlackHole hole{{}, 1, std::nullopt};
  Flight flight(camera_at({2.9, 0, 0}, 0));
  const auto refused = flight.start_orbit(hole);
  ASSERT_TRUE(refused);
  EXPECT_NE(refused->find("3M"), std::string::npos) << *refused;
  EXPECT_EQ(flight.mode, Flight::Mode::kPowered);
}

TEST(Flight, FallsFromRest) {
  const BlackHole hole{{}, 2, std::nullopt};  // M = 2
  const double r0 = 20, m = 2;
  Flight flight(camera_at({0, r0, 0}, -4));
  ASSERT_FALSE(flight.start_fall(hole));
  EXPECT_EQ(flight.mode, Flight::Mode::kFall);
  EXPECT_EQ(flight.speed, 0);
  ASSERT_TRUE(flight.advance(30, &hole));
  const double r = length(flight.camera.world_line.position);
  EXPECT_LT(r, r0);
  EXPECT_NEAR(flight.camera.world_line.position.x, 0, 1e-9);
  EXPECT_NEAR(flight.speed, std::sqrt(2 * m * (1 / r - 1 / r0)) / std::sqrt(1 - 2 * m / r0), 1e-9);
  EXPECT_LT(flight.camera.world_line.velocity.y, 0);
}

// A fall goes on through the horizon (the renderers draw the view from inside) to where they
// stop, r = kCameraInnermostRadius M; inside, boosts, stops and orbits are refused.
TEST(Flight, FallsThroughTheHorizonToTheInnermostRadius) {
  const BlackHole hole{{}, 1, std::nullopt};
  Flight flight(camera_at({0, 6, 0}, -4));
  ASSERT_FALSE(flight.start_fall(hole));
  EXPECT_FALSE(flight.inside_horizon());
  double least = 6;
  bool stopped = false;
  for (int i = 0; i < 10000 && !stopped; ++i) {
    stopped = !flight.advance(0.01, &hole);
    least = std::min(least, length(flight.camera.world_line.position));
  }
  ASSERT_TRUE(stopped);
  EXPECT_EQ(flight.mode, Flight::Mode::kFall);
  EXPECT_TRUE(flight.inside_horizon());
  EXPECT_LT(least, 0.06);
  EXPECT_GE(least, kCameraInnermostRadius);
  const double tau = flight.camera.motion.proper_time;
  flight.set_speed(0.5);
  EXPECT_EQ(flight.mode, Flight::Mode::kFall);
  EXPECT_EQ(flight.camera.motion.proper_time, tau);
  EXPECT_TRUE(flight.start_orbit(hole));
  EXPECT_TRUE(flight.start_fall(hole));
  EXPECT_FALSE(flight.advance(0.01, &hole));  // it stays at the end
}

TEST(Flight, SceneCameraOnAGeodesicGoesOnAlongIt) {
  Camera c;
  HoleOrbit orbit;
  orbit.radius = 8;
  c.motion.geodesic = HoleGeodesic{{}, 1, orbit};
  c.world_line = camera_observation(c.motion);
  Flight flight(c);
  EXPECT_EQ(flight.mode, Flight::Mode::kOrbit);
  ASSERT_TRUE(flight.advance(5));
  EXPECT_NEAR(length(flight.camera.world_line.position), 8, 1e-9);
}

}  // namespace
}  // namespace lightcone

namespace lightcone {
namespace {

// The viewer's first impression (viewer/frame_rate.hpp): the rate over two seconds after three
// warm-up frames, and advice below 20 fps naming the window's size, the GPU's tessellation where
// a hardware GPU could take it, and the split view.
TEST(FrameRate, MeasuredOnceAfterTheWarmUp) {
  FrameRateProbe probe;
  double t = 0;
  for (int i = 0; i < 3; ++i) EXPECT_FALSE(probe.frame(t += 1.0));  // slow first frames
  bool ended = false;
  int frames = 0;
  while (!ended) {
    ended = probe.frame(t += 0.125);  // eight frames a second, in steps exact in binary
    ++frames;
  }
  ASSERT_TRUE(probe.measured());
  EXPECT_EQ(*probe.measured(), 8.0);
  EXPECT_EQ(frames, 16);
  EXPECT_FALSE(probe.frame(t += 0.125));
}

TEST(FrameRate, AdviceNamesWhatToLower) {
  EXPECT_FALSE(slow_viewer_advice(25, 640, 360, false, true, false));
  const auto cpu = slow_viewer_advice(12.5, 1280, 720, false, true, true);
  ASSERT_TRUE(cpu);
  EXPECT_NE(cpu->find("12.5 frames a second"), std::string::npos) << *cpu;
  EXPECT_NE(cpu->find("1280x720"), std::string::npos);
  EXPECT_NE(cpu->find("--tessellation gpu"), std::string::npos);
  EXPECT_NE(cpu->find("split"), std::string::npos);
  const auto software = slow_viewer_advice(12.5, 640, 360, false, false, false);
  ASSERT_TRUE(software);
  EXPECT_EQ(software->find("--tessellation"), std::string::npos);
  EXPECT_EQ(software->find("split"), std::string::npos);
}

}  // namespace
}  // namespace lightcone

namespace lightcone {
namespace {

// The viewer's clock where none is given: 1 in flat space; near a hole the scene's shortest
// free fall from rest to r = 0, (pi/2) sqrt(r^3 / 2M), in kSceneSeconds.
TEST(DefaultTimeScale, ShowsTheScenesShortestFreeFallInSeconds) {
  const auto fall = [](double r) { return std::numbers::pi / 2 * std::sqrt(r * r * r / 2); };
  EXPECT_EQ(default_time_scale(test::load_repository_scene("terrell.json")), 1);
  // The clocks fall from 10M; the camera, at rest at 30M, would fall longer.
  const double infall = default_time_scale(test::load_repository_scene("infall.json"));
  EXPECT_NEAR(infall, fall(10) / kSceneSeconds, 1e-12);
  EXPECT_NEAR(infall, 3.512, 0.001);  // 35.12M of the clocks' own time in 10 s
  // The moon's orbit at 8M.
  EXPECT_NEAR(default_time_scale(test::load_repository_scene("orbit.json")),
              fall(8) / kSceneSeconds, 1e-12);
  // The camera alone, at rest at 60M: a fall from there (F) in 10 s, not 8.6 minutes.
  Scene hole = test::load_repository_scene("black-hole.json");
  const Vec3 offset = hole.camera.world_line.position - hole.black_hole->position;
  ASSERT_NEAR(length(offset), 60, 1e-3);
  EXPECT_NEAR(default_time_scale(hole), fall(length(offset)) / kSceneSeconds, 1e-9);
  // The hole's mass sets the scale: lengths and times twice as large, the clock twice as fast.
  hole.black_hole->mass = 2;
  hole.camera.world_line.position = hole.black_hole->position + offset * 2;
  EXPECT_NEAR(default_time_scale(hole), 2 * fall(length(offset)) / kSceneSeconds, 1e-9);
}

}  // namespace
}  // namespace lightcone
