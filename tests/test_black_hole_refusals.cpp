// What the loader and the commands refuse of a camera moving freely near a Schwarzschild black
// hole, and how they say it (docs/scene-format.md, "black_hole"): the motions' own mistakes, the
// proper times at which a falling camera is not drawn (with the radii in the scene's units and in
// M), the frame an animation stops at, named once, and what is not drawn from inside the
// horizon. The motions themselves are tests/test_black_hole_motion.cpp's.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "lightcone/physics/schwarzschild_geodesics.hpp"
#include "lightcone/scene/animation.hpp"
#include "support/scene_file_test.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;

using BlackHoleMotion = test::SceneFileTest;

// The camera's keys on line 2, the hole `hole` on line 3.
std::string camera_near(const std::string& camera, const std::string& hole = R"({"mass": 1})") {
  return "{\n  \"camera\": {" + camera + "},\n  \"black_hole\": " + hole + "\n}";
}

TEST_F(BlackHoleMotion, Refusals) {
  const auto flat = [](const std::string& motion) {
    return "{\n  \"camera\": {\"position\": [0, 0, 20],\n    \"motion\": " + motion + "}\n}";
  };
  expect_error(flat(R"({"orbit": {"radius": 10}})"), 3, "camera.motion.orbit",
               "a circular orbit about a black hole needs a black hole (the top-level "
               "\"black_hole\")");
  expect_error(flat(R"({"fall": {"from": "infinity"}})"), 3, "camera.motion.fall",
               "a free fall toward a black hole needs a black hole");
  // Phases and keyframes stay refused near a hole, and so does a proper time without a motion.
  expect_error(
      camera_near(
          R"("position": [0, 0, 50], "motion": {"phases": [{"duration": 1, "acceleration": [1, 0, 0]}]})"),
      2, "camera.motion",
      "motion (phases or keyframes) of the camera is not yet supported near a black "
      "hole: near one the camera moves on a geodesic, \"orbit\" or \"fall\"");
  expect_error(camera_near(R"("position": [0, 0, 50], "proper_time": 3)"), 2, "camera.proper_time",
               "a proper time other than 0 without a camera motion is not yet supported near a "
               "black hole");
  expect_error(
      camera_near(R"("motion": {"fall": {"from": 10, "direction": [0, 0, 1]}}, "shutter": 1)"), 2,
      "camera.shutter", "is not yet supported near a black hole");
  expect_error(camera_near(R"("motion": {}, "position": [0, 0, 30])"), 2, "camera.motion",
               "must have exactly one of: orbit, fall (found none)");
  expect_error(camera_near(R"("motion": {"orbit": {"radius": 10}, "fall": {}})"), 2,
               "camera.motion", "must have exactly one of: orbit, fall (found orbit, fall)");
  // The orbit.
  for (const char* key :
       {R"("position": [0, 0, 10])", R"("time": 1)", R"("velocity": [0.1, 0, 0])"})
    expect_error(camera_near(std::string(key) + R"(, "motion": {"orbit": {"radius": 10}})"), 2,
                 std::string("camera.") + (key[1] == 'p'   ? "position"
                                           : key[1] == 't' ? "time"
                                                           : "velocity"),
                 "must not be given with motion.orbit (the orbit says where and when the camera "
                 "is and how it moves");
  expect_error(camera_near(R"("motion": {"orbit": {}})"), 2, "camera.motion.orbit.radius",
               "required key is missing");
  for (const char* r : {"3", "2", "-5"})
    expect_error(camera_near(fmt::format(R"("motion": {{"orbit": {{"radius": {}}}}})", r)), 2,
                 "camera.motion.orbit.radius",
                 "is not outside the photon sphere, 3M: a circular orbit's radius (in units of M) "
                 "must be greater than 3 (and orbits inside 6M, the ISCO, are unstable)");
  expect_error(camera_near(R"("motion": {"orbit": {"radius": 3.0000000000001}})"), 2,
               "camera.motion.orbit.radius",
               "measured by the local static observer is too close to the speed of light");
  expect_error(camera_near(R"("motion": {"orbit": {"radius": 10, "normal": [0, 0, 0]}})"), 2,
               "camera.motion.orbit.normal", "must not be the zero vector");
  expect_error(camera_near(R"("motion": {"orbit": {"radius": 10, "axis": [0, 1, 0]}})"), 2,
               "camera.motion.orbit.axis",
               "unknown key \"axis\" (expected one of: radius, normal, phase)");
  // The fall.
  expect_error(camera_near(R"("position": [0, 0, 9], "time": 1, "motion": {"fall": {}})"), 2,
               "camera.time",
               "must not be given with motion.fall (the coordinate time at the "
               "camera's proper time 0 is motion.fall.time)");
  expect_error(
      camera_near(R"("position": [0, 0, 9], "velocity": [0, 0, -0.1], "motion": {"fall": {}})"), 2,
      "camera.velocity",
      "must not be given with motion.fall (the camera falls freely "
      "from rest");
  expect_error(camera_near(R"("motion": {"fall": {"direction": [0, 0, 1]}})"), 2,
               "camera.motion.fall", "needs \"from\": the radius r0 in units of M (> 2)");
  expect_error(camera_near(R"("motion": {"fall": {"from": 10}})"), 2, "camera.motion.fall",
               "needs \"direction\" [x, y, z], from the black hole along which the camera falls");
  expect_error(camera_near(R"("motion": {"fall": {"from": "infinity", "direction": [0, 0, 1]}})"),
               2, "camera.motion.fall",
               "a fall from \"infinity\" needs camera.position: where the camera passes at its "
               "proper time 0");
  for (const char* from : {"2", "1", "0", "-3"})
    expect_error(camera_near(fmt::format(
                     R"("motion": {{"fall": {{"from": {}, "direction": [0, 0, 1]}}}})", from)),
                 2, "camera.motion.fall.from",
                 "is not outside the horizon, 2M: the radius (in units of M) where the camera "
                 "falls from rest must be greater than 2, or \"infinity\"");
  expect_error(camera_near(R"("motion": {"fall": {"from": "far", "direction": [0, 0, 1]}})"), 2,
               "camera.motion.fall.from", "must be a number (the radius r0 in units of M, > 2");
  expect_error(camera_near(R"("position": [0, 0, 30], "motion": {"fall": {"from": 20}})"), 2,
               "camera.motion.fall.from",
               "the fall from rest at r0 = 20M starts at r = 20 from the black hole, but "
               "camera.position, where it is at proper time 0, is at r = 30 (30M): give one of "
               "them");
  expect_error(
      camera_near(R"("position": [0, 0, 30], "motion": {"fall": {"direction": [0, 0, -1]}})"), 2,
      "camera.motion.fall.direction", "must point from the black hole toward camera.position");
  expect_error(camera_near(R"("position": [0, 0, 1.5], "motion": {"fall": {"from": "infinity"}})"),
               2, "camera.position", "inside its horizon r = 2M = 2");
  // So far along that the coordinate time overflows.
  expect_error(camera_near(R"("motion": {"orbit": {"radius": 3.5}}, "proper_time": 1.7e308)"), 2,
               "camera.proper_time",
               "at proper time 1.7e+308 the camera's coordinate time or distance from the black "
               "hole is not a finite number (it is too far along its orbit)");
  expect_error(
      camera_near(
          R"("position": [0, 0, 30], "motion": {"fall": {"from": "infinity", "time": -1e308}}, "proper_time": -1e308)"),
      2, "camera.proper_time", "is not a finite number (it is too far along its fall)");
  expect_error(
      camera_near(R"("motion": {"fall": {"from": 10, "direction": [0, 0, 1], "start": 1}})"), 2,
      "camera.motion.fall.start", "unknown key \"start\" (expected one of: from, direction, time)");
}

TEST_F(BlackHoleMotion, TheFallIsDrawnThroughTheHorizonDownTo005M) {
  const RadialFall fall = RadialFall::from_rest(1, 10);
  const double outside = fall.proper_time_at_radius(2 * (1 + 1e-9));
  const auto at = [](double tau) {
    return camera_near(fmt::format(
        R"("motion": {{"fall": {{"from": 10, "direction": [0, 0, 1]}}}}, "proper_time": {:.17g})",
        tau));
  };
  // Just outside 2M (1 + 1e-9): its speed near that of light but within the limit.
  const Scene close = load(at(outside * (1 - 1e-15)));
  EXPECT_GT(close.camera.world_line.position.z, 2);
  EXPECT_LT(close.camera.world_line.position.z, 2 + 1e-8);
  EXPECT_GT(-close.camera.world_line.velocity.z, 0.9999);
  // At and inside the horizon: drawn, from its fall (no static observer, no velocity in W).
  for (const double tau :
       {outside * (1 + 1e-12), fall.horizon_proper_time(), fall.proper_time_at_radius(0.06)}) {
    const Scene inside = load(at(tau));
    EXPECT_LE(inside.camera.world_line.position.z, 2 * (1 + 1e-9));
    EXPECT_EQ(inside.camera.world_line.velocity, Vec3{});
    EXPECT_TRUE(camera_inside_horizon(inside.camera.motion));
  }
  // Down to r = 0.05M; and not before it came to rest at r0, rising out of the past horizon.
  const double innermost = fall.proper_time_at_radius(0.05);
  expect_error(at(40), 2, "camera.proper_time",
               fmt::format("at proper time 40 the falling camera has reached the singularity r = "
                           "0 (at proper time {}): the camera is drawn down to r = 0.05M (it is "
                           "drawn at proper times between",
                           fall.proper_time_at_radius(0)));
  expect_error(at(innermost * (1 + 1e-12)), 2, "camera.proper_time", "within 0.05M");
  expect_error(at(-outside), 2, "camera.proper_time",
               "the falling camera, on its way to rest at r0 = 10M at proper time 0, is rising at "
               "r = 2.000000002 (2.000000002M), within 2M (1 + 1e-09) = 2.000000002 of the black "
               "hole, just out of its past horizon: rising, the camera is drawn only outside");
  expect_error(at(-100), 2, "camera.proper_time",
               fmt::format("does not exist yet (its geodesic begins at the past singularity r = 0 "
                           "at proper time {})",
                           -fall.proper_time_at_radius(0)));
  // From infinity only a later end; in the scene's units of time.
  const std::string message = error(
      "{\n  \"speed_of_light\": 2,\n  \"camera\": {\"position\": [0, 0, 30], \"motion\": "
      "{\"fall\": "
      "{\"from\": \"infinity\"}}, \"proper_time\": 100},\n  \"black_hole\": {\"mass\": 1}\n}");
  const double limit = RadialFall::from_infinity(1, 30).proper_time_at_radius(0.05) / 2;
  EXPECT_NE(message.find(fmt::format("(it is drawn at proper times below {})", limit)),
            std::string::npos)
      << message;
  EXPECT_NE(message.find(":3: camera.proper_time: at proper time 100 the falling camera"),
            std::string::npos)
      << message;
}

// Released from rest just outside the horizon but within 2M (1 + 1e-9), the camera is not drawn
// at rest there; the message says so (it used to call it rising out of the past horizon).
TEST_F(BlackHoleMotion, AFallFromRestWithinTheMarginIsRefusedAtRestNotAsRising) {
  const auto from = [](const std::string& r0, const std::string& tau) {
    return camera_near(R"("motion": {"fall": {"from": )" + r0 +
                       R"(, "direction": [0, 0, 1]}}, "proper_time": )" + tau);
  };
  const std::string message = error(from("2.000000001", "0"));
  expect_error(from("2.000000001", "0"), 2, "camera.proper_time",
               "at proper time 0 the falling camera is at rest at r0 = 2.000000001M "
               "(camera.motion.fall.from, or camera.position's distance from the hole), within "
               "2M (1 + 1e-09) = 2.000000002 of the black hole: at rest or rising the camera is "
               "drawn only outside that radius, falling also inside it (it is drawn at proper "
               "times between 0 and ");
  EXPECT_EQ(message.find("past horizon"), std::string::npos) << message;
  EXPECT_EQ(message.find("-0 "), std::string::npos) << message;
  // Falling, it is drawn from there on.
  EXPECT_EQ(error(from("2.000000001", "1e-6")), "");
  // Released outside the margin it is drawn from proper time 0 on, and before that while it
  // rose outside the margin; rising within it, it is refused as just out of the past horizon.
  const double rose = RadialFall::from_rest(1, 2.000000003).proper_time_at_radius(2 * (1 + 1e-9));
  for (const double tau : {0.0, -rose / 2})
    EXPECT_EQ(error(from("2.000000003", fmt::format("{:.17g}", tau))), "") << tau;
  expect_error(from("2.000000003", fmt::format("{:.17g}", -rose * 1.5)), 2, "camera.proper_time",
               "just out of its past horizon: rising, the camera is drawn only outside r = 2M "
               "(1 + 1e-09) = 2.000000002");
}

// Radii where M is not 1: in the scene's units and in units of M.
TEST_F(BlackHoleMotion, RefusedFallMessagesGiveRadiiInBothUnits) {
  const RadialFall fall = RadialFall::from_rest(2, 20);
  const auto at = [](double tau) {
    return camera_near(
        fmt::format(
            R"("motion": {{"fall": {{"from": 10, "direction": [0, 0, 1]}}}}, "proper_time": {:.17g})",
            tau),
        R"({"mass": 2})");
  };
  const double rising = -fall.horizon_proper_time() - 0.1;
  expect_error(at(rising), 2, "camera.proper_time",
               fmt::format("on its way to rest at r0 = 10M at proper time 0, is rising at r = "
                           "{0:.12g} ({1:.12g}M), inside the black hole's past horizon r = 2M = 4, "
                           "out of which it comes at proper time {2}: rising, the camera is drawn "
                           "only outside r = 2M (1 + 1e-09) = 4.000000004",
                           fall.at_proper_time(rising).radius,
                           fall.at_proper_time(rising).radius / 2, -fall.horizon_proper_time()));
  const double deep = (fall.proper_time_at_radius(0.1) + fall.proper_time_at_radius(0)) / 2;
  const double r = fall.at_proper_time(deep).radius;
  ASSERT_LT(r, 0.1);
  expect_error(at(deep), 2, "camera.proper_time",
               fmt::format("the falling camera is at r = {:.12g} ({:.12g}M), within 0.05M of the "
                           "singularity",
                           r, r / 2));
}

// A scene's own mistakes near the hole, named as the file spells them.
TEST_F(BlackHoleMotion, FallAndOrbitRefusalsNameTheFieldsAndTheirUnits) {
  const auto object = [](const std::string& keys, const std::string& hole = R"({"mass": 1})") {
    return "{\n  \"camera\": {\"position\": [0, 0, 60]},\n  \"black_hole\": " + hole +
           ",\n  \"objects\": [{\"name\": \"a\", \"shape\": {\"sphere\": {\"radius\": "
           "3}}, " +
           keys + "}]\n}";
  };
  const std::string infinity = error(object(R"("motion": {"fall": {"from": "infinity"}})"));
  expect_error(object(R"("motion": {"fall": {"from": "infinity"}})"), 4, "objects[0].motion.fall",
               "a fall from \"infinity\" needs objects[0].position: where the object passes");
  EXPECT_EQ(infinity.find("object.position"), std::string::npos) << infinity;
  expect_error(object(R"("position": [0, 0, 10], "motion": {"fall": {"direction": [1, 0, 0]}})"), 4,
               "objects[0].motion.fall.direction",
               "must point from the black hole toward objects[0].position, where the object is");
  expect_error(object(R"("motion": {"fall": {"from": 10}})"), 4, "objects[0].motion.fall",
               "needs \"direction\" [x, y, z], from the black hole along which the object falls "
               "(or objects[0].position)");
  // The orbit's radius is given in units of M: so is the least it may be.
  expect_error(object(R"("motion": {"orbit": {"radius": 3.5}})", R"({"mass": 2})"), 4,
               "objects[0].motion.orbit.radius",
               "on an orbit at r = 7 it crosses the horizon r = 2M = 4: an orbit's radius must "
               "exceed 2M plus the object's reach (here a radius above 3.5, in units of M)");
  // A falling camera's position is its event at proper time 0, not a static observer's place.
  const std::string inside =
      camera_near(R"("position": [0, 0, 1.5], "motion": {"fall": {"from": "infinity"}})");
  expect_error(inside, 2, "camera.position",
               "the camera is at r = 1.5 from the black hole, inside its horizon r = 2M = 2: on a "
               "fall this is where the camera is at its proper time 0, at coordinate time "
               "motion.fall.time, and W's time is not defined inside the horizon");
  EXPECT_EQ(error(inside).find("static observer"), std::string::npos) << error(inside);
  // An orbit's camera has no position to give, inside the horizon or out.
  expect_error(camera_near(R"("position": [0, 0, 1.5], "motion": {"orbit": {"radius": 10}})"), 2,
               "camera.position", "must not be given with motion.orbit");
}

// An animation's refusals name their frame once, in the library (the Python module's
// animation_frame shows its reason as it is) and through the command.
TEST_F(BlackHoleMotion, AnAnimationFrameIsNamedOnce) {
  const Scene scene =
      load(camera_near(R"("motion": {"fall": {"from": 10, "direction": [0, 0, 1]}})"));
  Scene frame;
  const auto why = animation_frame(scene, 4, 0.1, AnimationClock::kCamera, frame);
  ASSERT_TRUE(why);
  EXPECT_TRUE(
      why->starts_with("frame 4: at proper time 40 the falling camera has reached the "
                       "singularity"))
      << *why;
  const fs::path falling =
      write("falling.json",
            "{\"camera\": {\"width\": 16, \"height\": 9, \"samples\": 1, \"motion\": {\"fall\": "
            "{\"from\": 10, \"direction\": [0, 0, 1]}}},\n \"black_hole\": {\"mass\": 1},\n "
            "\"objects\": [{\"name\": \"o\", \"shape\": {\"sphere\": {\"radius\": 0.3}}, "
            "\"position\": [10, 0, 0]}],\n \"render\": {\"exposure\": 0}}");
  // From rest at 10M the camera reaches the horizon at proper time 33.70.
  const test::CommandResult r =
      test::run_lightcone("animate " + test::quoted(falling) + " --fps 1 --frames 33-34 -o " +
                          test::quoted(dir_ / "f%d.png") + " --quiet");
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(
      r.err.starts_with("lightcone: frame 34: by then the falling camera has reached the "
                        "black hole's horizon (it is at r = "))
      << r.err;
  EXPECT_NE(r.err.find(", not outside 2M (1 + 1e-09) = 2.000000002), where objects are not drawn "
                       "yet"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("frame 34: frame 34"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "f33.png"));
  // A camera moving without a geodesic is refused on its velocity.
  const fs::path moving = write("moving.json",
                                "{\"camera\": {\"position\": [0, 0, 30], \"velocity\": [0.1, "
                                "0, 0]},\n \"black_hole\": {\"mass\": 1}}");
  const test::CommandResult m =
      test::run_lightcone("animate " + test::quoted(moving) + " --fps 1 --frames 0-1 -o " +
                          test::quoted(dir_ / "m%d.png") + " --quiet");
  EXPECT_EQ(m.status, 2);
  EXPECT_NE(m.err.find("moving.json: camera.velocity: a camera that moves near a black hole is "
                       "animated along a geodesic motion"),
            std::string::npos)
      << m.err;
}

TEST_F(BlackHoleMotion, InsideTheHorizonObjectsAndTheRasterAreRefused) {
  const RadialFall fall = RadialFall::from_rest(1, 10);
  const std::string inside = fmt::format(
      R"("motion": {{"fall": {{"from": 10, "direction": [0, 0, 1]}}}}, "proper_time": {:.17g})",
      fall.proper_time_at_radius(1.5));
  expect_error(
      "{\n  \"camera\": {" + inside +
          "},\n  \"black_hole\": {\"mass\": 1},\n  \"objects\": [{\"name\": \"a\", "
          "\"shape\": {\"sphere\": {\"radius\": 1}}, \"position\": [0, 0, -10]}]\n}",
      4, "objects",
      "objects seen from inside the black hole's horizon are not drawn yet (the falling camera "
      "is at r = 1.5 there");
}

}  // namespace
}  // namespace lightcone
