// Bodies placed by where they are seen ("seen_at", scene/scene.hpp place_where_seen): locate
// finds each body's origin at the pixel of a point at rest in W at seen_at, for inertial,
// accelerated and keyframed bodies, a moving camera and a slow speed of light, and near a black
// hole on the exact ray; the key's errors name the file, line and field; and check and info warn
// of bodies the camera does not see.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "lightcone/frame/locate.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;
using test::quoted;
using test::run_lightcone;

nlohmann::json locate(const fs::path& scene, const std::string& what) {
  const test::CommandResult r = run_lightcone("locate " + quoted(scene) + " " + what);
  EXPECT_EQ(r.status, 0) << r.err;
  return nlohmann::json::parse(r.out);
}

TEST(SeenAt, EachBodyIsSeenWhereAPointAtRestThereIs) {
  const fs::path dir = test::fresh_temp_dir("seen-at");
  for (const char* speed_of_light : {"1", "0.5"}) {
    test::write_text(dir / "scene.json", std::string(R"({"speed_of_light": )") + speed_of_light +
                                             R"(,
  "camera": {"position": [0, 1, 5], "velocity": [0.15, 0, -0.1], "time": 2},
  "objects": [
    {"name": "cube", "shape": {"box": {"size": [1, 1, 1]}}, "seen_at": [2, 1, -8],
     "velocity": [-0.45, 0, 0]},
    {"name": "rocket", "shape": {"sphere": {"radius": 0.1}}, "seen_at": [-3, 2, -6],
     "velocity": [0.1, 0, 0], "motion": {"phases": [{"duration": 5, "acceleration": [0.1, 0, 0.05]}]}},
    {"name": "drone", "shape": {"sphere": {"radius": 0.1}}, "seen_at": [0, 0, -4],
     "motion": {"keyframes": [{"time": -20, "position": [0, 0, 0]}, {"time": -5, "position": [3, 1, 0]},
                              {"time": 5, "position": [4, 3, -2]}]}}
  ]
})");
    for (const auto& [name, seen] : {std::pair{"cube", "2,1,-8"}, std::pair{"rocket", "-3,2,-6"},
                                     std::pair{"drone", "0,0,-4"}}) {
      const nlohmann::json body =
          locate(dir / "scene.json", std::string("--object ") + name + " --point 0,0,0");
      const nlohmann::json point = locate(dir / "scene.json", std::string("--world-point ") + seen);
      ASSERT_TRUE(body["in_view"].get<bool>()) << name;
      for (int k = 0; k < 2; ++k)
        EXPECT_NEAR(body["pixel"][k].get<double>(), point["pixel"][k].get<double>(), 0.5)
            << name << " at c = " << speed_of_light;
      // The light left the origin at seen_at itself.
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(body["emission_position"][k].get<double>(),
                    point["emission_position"][k].get<double>(), 1e-9)
            << name;
    }
  }
  fs::remove_all(dir);
}

TEST(SeenAt, ReplacesPositionAndTimeAndNearABlackHoleNeedsALine) {
  const fs::path dir = test::fresh_temp_dir("seen-at-errors");
  test::write_text(dir / "both.json", R"({
  "camera": {"position": [0, 0, 5]},
  "objects": [{"name": "cube", "shape": {"box": {"size": [1, 1, 1]}},
               "position": [0, 0, -3], "seen_at": [0, 0, -3]}]
})");
  test::CommandResult r = run_lightcone("check " + quoted(dir / "both.json"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("both.json:4: objects[0].seen_at: replaces \"position\" and \"time\""),
            std::string::npos)
      << r.err;
  const auto near_hole = [&](const std::string& object) {
    test::write_text(dir / "hole.json", R"({
  "black_hole": {"mass": 1},
  "camera": {"position": [0, 0, 30]},
  "objects": [{"name": "cube", "shape": {"box": {"size": [1, 1, 1]}}, )" +
                                            object + R"(}]
})");
    return run_lightcone("check " + quoted(dir / "hole.json"));
  };
  r = near_hole(R"("seen_at": [1, 0, 0.5])");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("hole.json:4: objects[0].seen_at: no light leaves (1, 0, 0.5)"),
            std::string::npos)
      << r.err;
  r = near_hole(R"("seen_at": [0, 0, -30], "motion": {"orbit": {"radius": 12}})");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("objects[0].seen_at: a geodesic motion"), std::string::npos) << r.err;
  r = near_hole(R"("seen_at": [2, 0, -30])");
  EXPECT_EQ(r.status, 0) << r.err;
  fs::remove_all(dir);
}

// Near a black hole the origin of a body at rest or on a line is seen, in its primary image,
// where a point at rest at seen_at is: its light left seen_at itself, at the time the lens's
// exact ray gives (the Shapiro delay in it), behind the hole as beside it.
TEST(SeenAt, NearABlackHoleThePrimaryImageOfTheOriginIsAtSeenAt) {
  const Scene s = test::scene_from_json(R"({
  "black_hole": {"mass": 1},
  "camera": {"position": [0, 0, 30], "time": 3, "velocity": [0.1, 0.05, -0.2]},
  "objects": [
    {"name": "behind", "shape": {"box": {"size": [1, 1, 1]}}, "seen_at": [1, 0.5, -12],
     "velocity": [0.4, 0, 0.2]},
    {"name": "beside", "shape": {"sphere": {"radius": 0.5}}, "seen_at": [9, 2, 4],
     "velocity": [0, -0.3, 0]},
    {"name": "still", "shape": {"sphere": {"radius": 0.5}}, "seen_at": [-5, 0, -6]}
  ]})");
  for (const auto& [name, seen] :
       {std::pair{"behind", Vec3{1, 0.5, -12}}, std::pair{"beside", Vec3{9, 2, 4}},
        std::pair{"still", Vec3{-5, 0, -6}}}) {
    SCOPED_TRACE(name);
    const LocateResult body = locate(s, {LocateQuery::Kind::ObjectPoint, name, {}});
    const LocateResult point = locate(s, {LocateQuery::Kind::WorldPoint, {}, seen});
    ASSERT_FALSE(body.images.empty());
    ASSERT_FALSE(point.images.empty());
    EXPECT_EQ(body.images[0].order, 0);
    test::expect_vec(*body.images[0].emission_position, seen, 1e-9 * length(seen));
    EXPECT_NEAR(*body.images[0].emission_time, *point.images[0].emission_time,
                1e-9 * std::abs(*point.images[0].emission_time));
    test::expect_vec(body.images[0].direction, point.images[0].direction, 1e-9);
  }
}

// A hole of 1e-9 units far away places each body where flat spacetime does.
TEST(SeenAt, ANegligibleHolePlacesBodiesAsFlatSpacetime) {
  const std::string bodies = R"(
  "camera": {"position": [0, 1, 5], "time": 2},
  "objects": [
    {"name": "cube", "shape": {"box": {"size": [1, 1, 1]}}, "seen_at": [2, 1, -8],
     "velocity": [-0.45, 0, 0]},
    {"name": "ball", "shape": {"sphere": {"radius": 0.5}}, "seen_at": [-3, 2, -6]}])";
  const Scene flat = test::scene_from_json("{" + bodies + "}");
  const Scene near = test::scene_from_json(
      "{" + bodies + R"(, "black_hole": {"mass": 1e-9, "position": [500, 500, 500]}})");
  for (std::size_t i = 0; i < flat.objects.size(); ++i)
    test::expect_vec(near.objects[i].world_line.position, flat.objects[i].world_line.position,
                     1e-6);
}

// check and info name each moving body the camera cannot see, and where it is seen; seen_at
// fixes it.
TEST(SeenAt, CheckAndInfoWarnOfBodiesOutOfView) {
  const fs::path dir = test::fresh_temp_dir("seen-at-warnings");
  const auto scene = [&](const std::string& cube) {
    test::write_text(dir / "scene.json", R"({
  "camera": {"position": [0, 1, 4], "fov": 60},
  "objects": [
    {"name": "floor", "shape": {"plane": {"size": [40, 40]}}, "position": [0, 0, -8]},
    {"name": "behind", "shape": {"sphere": {"radius": 0.5}}, "position": [0, 1, 9],
     "velocity": [0.1, 0, 0]},
    {"name": "still", "shape": {"sphere": {"radius": 0.5}}, "position": [0, 1, 12]},
    {"name": "cube", "shape": {"box": {"size": [1, 1, 1]}}, "velocity": [0.9, 0, 0], )" +
                                             cube + "}]}");
    return dir / "scene.json";
  };
  for (const char* command : {"check ", "info "}) {
    const test::CommandResult r =
        run_lightcone(command + quoted(scene(R"("position": [0, 1, -8])")));
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.err.find("warning: object \"cube\" is seen out of view, at pixel ("),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("warning: object \"behind\" is seen behind the camera"), std::string::npos)
        << r.err;
    // A body at rest is seen where it is: out of view only by the scene's framing.
    EXPECT_EQ(r.err.find("\"still\""), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("\"seen_at\" places a body by where it is seen"), std::string::npos);
  }
  const test::CommandResult placed =
      run_lightcone("check " + quoted(scene(R"("seen_at": [0, 1, -8])")));
  EXPECT_EQ(placed.err.find("\"cube\""), std::string::npos) << placed.err;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lightcone
