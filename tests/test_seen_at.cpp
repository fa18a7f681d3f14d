// Bodies placed by where they are seen ("seen_at", scene/scene.hpp place_where_seen): locate
// finds each body's origin at the pixel of a point at rest in W at seen_at, for inertial,
// accelerated and keyframed bodies, a moving camera and a slow speed of light; the key's errors
// name the file, line and field; and check and info warn of bodies the camera does not see.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

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

TEST(SeenAt, ReplacesPositionAndTimeAndIsRefusedNearABlackHole) {
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
  test::write_text(dir / "hole.json", R"({
  "black_hole": {"mass": 1},
  "camera": {"position": [0, 0, 30]},
  "objects": [{"name": "cube", "shape": {"box": {"size": [1, 1, 1]}}, "seen_at": [0, 0, -30]}]
})");
  r = run_lightcone("check " + quoted(dir / "hole.json"));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("hole.json:4: objects[0].seen_at"), std::string::npos) << r.err;
  fs::remove_all(dir);
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
