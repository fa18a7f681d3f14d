// `lightcone locate` through the real binary: known values of where a world point, an object
// and a direction are seen, their Doppler factors, and points the camera cannot see.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "lightcone/io/image_file.hpp"
#include "lightcone/physics/aberration.hpp"
#include "support/cli_test.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;
using namespace test;  // the CLI fixture and helpers (support/cli_test.hpp)

// ----------------------------------------------------------------------------------------------
// locate

// Parses locate's stdout: one line, one JSON object with exactly the contract's keys in order.
nlohmann::ordered_json locate_output(const CommandResult& r) {
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(line_count(r.out), 1u) << r.out;
  const auto out = nlohmann::ordered_json::parse(r.out, nullptr, false);
  EXPECT_TRUE(out.is_object()) << r.out;
  if (!out.is_object()) return nlohmann::ordered_json::object();
  std::vector<std::string> keys;
  for (const auto& item : out.items()) keys.push_back(item.key());
  EXPECT_EQ(keys,
            (std::vector<std::string>{"pixel", "direction", "emission_time", "emission_position",
                                      "emission_proper_time", "distance", "in_view", "doppler"}));
  // A pixel where the point is in view, null where it is behind the camera or off the image.
  if (out["in_view"].get<bool>())
    EXPECT_TRUE(out["pixel"].is_array() && out["pixel"].size() == 2) << r.out;
  else
    EXPECT_TRUE(out["pixel"].is_null()) << r.out;
  EXPECT_TRUE(out["doppler"].is_number() && out["doppler"].get<double>() > 0) << r.out;
  EXPECT_TRUE(out["direction"].is_array() && out["direction"].size() == 3) << r.out;
  EXPECT_TRUE(out["in_view"].is_boolean()) << r.out;
  return out;
}

double at(const nlohmann::ordered_json& j, const char* key, std::size_t i) {
  return j.at(key).at(i).get<double>();
}

// Near a black hole, --object gives every image of a body's point with its clock reading: the
// clock let go last in infall.json, seen held at rest (clock negative) in its secondary and
// third images, falling in its primary; their emission times in the order of the images.
TEST_F(CliTest, LocateAnObjectNearABlackHole) {
  const CommandResult r = locate(fs::path(LIGHTCONE_SOURCE_DIR) / "scenes/infall.json",
                                 "--object late --point 0,0,0.8");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto out = nlohmann::ordered_json::parse(r.out);
  const auto& images = out.at("images");
  ASSERT_EQ(images.size(), 3u);
  EXPECT_GT(images[0]["emission_proper_time"].get<double>(), 0);
  EXPECT_LT(images[1]["emission_proper_time"].get<double>(), 0);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(images[k]["order"].get<int>(), k);
  EXPECT_GT(images[0]["emission_time"].get<double>(), images[1]["emission_time"].get<double>());
  EXPECT_GT(images[1]["emission_time"].get<double>(), images[2]["emission_time"].get<double>());
  EXPECT_EQ(out["emission_proper_time"], images[0]["emission_proper_time"]);
}

TEST_F(CliTest, LocateWorldPointKnownValues) {
  const fs::path scene = write_scene(kScene);
  // Camera at rest at the origin: a point 10 ahead is in the image centre, 10 away, emitted at
  // t = -10 where it is.
  const auto still = locate_output(locate(scene, "--world-point 0,0,-10"));
  ASSERT_FALSE(still.empty());
  EXPECT_NEAR(at(still, "pixel", 0), 32, 1e-9);
  EXPECT_NEAR(at(still, "pixel", 1), 24, 1e-9);
  EXPECT_NEAR(at(still, "direction", 0), 0, 1e-12);
  EXPECT_NEAR(at(still, "direction", 1), 0, 1e-12);
  EXPECT_NEAR(at(still, "direction", 2), -1, 1e-12);
  EXPECT_NEAR(still["emission_time"].get<double>(), -10, 1e-9);
  EXPECT_NEAR(at(still, "emission_position", 2), -10, 1e-9);
  EXPECT_NEAR(still["distance"].get<double>(), 10, 1e-9);
  EXPECT_TRUE(still["in_view"].get<bool>());

  // The camera flying at 0.6c toward it: same emission event, but in the camera's frame the
  // light travelled gamma (1 + beta) 10 = 20.
  const auto flying =
      locate_output(locate(scene, "--world-point 0,0,-10 --set 'camera.velocity=[0,0,-0.6]'"));
  ASSERT_FALSE(flying.empty());
  EXPECT_NEAR(at(flying, "pixel", 0), 32, 1e-9);
  EXPECT_NEAR(at(flying, "pixel", 1), 24, 1e-9);
  EXPECT_NEAR(flying["emission_time"].get<double>(), -10, 1e-9);
  EXPECT_NEAR(at(flying, "emission_position", 0), 0, 1e-9);
  EXPECT_NEAR(at(flying, "emission_position", 2), -10, 1e-9);
  EXPECT_NEAR(flying["distance"].get<double>(), 20, 1e-9);

  // Off axis, above and to the right: x grows to the right, y downwards. fov 30 over 48 rows:
  // focal length 24 / tan(15 deg) pixels.
  const double focal = 24 / std::tan(15 * std::acos(-1.0) / 180);
  const auto off = locate_output(locate(scene, "--world-point 1,0.5,-10"));
  ASSERT_FALSE(off.empty());
  EXPECT_NEAR(at(off, "pixel", 0), 32 + focal * 0.1, 1e-9);
  EXPECT_NEAR(at(off, "pixel", 1), 24 - focal * 0.05, 1e-9);
  EXPECT_NEAR(off["distance"].get<double>(), std::sqrt(1 + 0.25 + 100), 1e-9);

  // Behind the camera.
  const auto behind = locate_output(locate(scene, "--world-point 0,0,10"));
  ASSERT_FALSE(behind.empty());
  EXPECT_FALSE(behind["in_view"].get<bool>());
  // Far to the side, in front.
  const auto aside = locate_output(locate(scene, "--world-point 100,0,-10"));
  ASSERT_FALSE(aside.empty());
  EXPECT_FALSE(aside["in_view"].get<bool>());
}

TEST_F(CliTest, LocateDirectionHasNoEmissionEvent) {
  const fs::path scene = write_scene(kScene);
  const auto ahead = locate_output(locate(scene, "--direction 0,0,-3"));
  ASSERT_FALSE(ahead.empty());
  EXPECT_NEAR(at(ahead, "pixel", 0), 32, 1e-9);
  EXPECT_NEAR(at(ahead, "pixel", 1), 24, 1e-9);
  EXPECT_NEAR(at(ahead, "direction", 2), -1, 1e-12);
  EXPECT_TRUE(ahead["emission_time"].is_null());
  EXPECT_TRUE(ahead["emission_position"].is_null());
  EXPECT_TRUE(ahead["distance"].is_null());
  EXPECT_TRUE(ahead["in_view"].get<bool>());

  // A camera flying along +x at 0.6c sees the direction perpendicular to its motion tilted
  // forward: the apparent direction is (beta, 0, -1/gamma) = (0.6, 0, -0.8).
  const auto tilted =
      locate_output(locate(scene, "--direction 0,0,-1 --set 'camera.velocity=[0.6,0,0]'"));
  ASSERT_FALSE(tilted.empty());
  EXPECT_NEAR(at(tilted, "direction", 0), 0.6, 1e-12);
  EXPECT_NEAR(at(tilted, "direction", 1), 0, 1e-12);
  EXPECT_NEAR(at(tilted, "direction", 2), -0.8, 1e-12);
  EXPECT_FALSE(tilted["in_view"].get<bool>());  // 37 degrees off axis, the half-width is ~21

  // Directions are scaled before they are normalised: huge and tiny components work alike.
  for (const char* direction : {"0,0,-1e300", "0,0,-1e-300"}) {
    const auto scaled = locate_output(locate(scene, std::string("--direction ") + direction));
    ASSERT_FALSE(scaled.empty()) << direction;
    EXPECT_NEAR(at(scaled, "pixel", 0), 32, 1e-9) << direction;
    EXPECT_NEAR(at(scaled, "direction", 2), -1, 1e-12) << direction;
  }
}

// locate's "doppler" is D = nu_camera / nu_emitter (PHYSICS.md, "Doppler factor").
TEST_F(CliTest, LocateDopplerFactor) {
  const fs::path scene = write_scene(kScene);
  auto doppler = [&](const std::string& query) {
    const auto out = locate_output(locate(scene, query));
    return out.empty() ? -1.0 : out["doppler"].get<double>();
  };
  // Camera and point at rest: no shift at all.
  EXPECT_EQ(doppler("--world-point 0,0,-10"), 1.0);
  EXPECT_EQ(doppler("--world-point 3,-2,-10"), 1.0);
  EXPECT_EQ(doppler("--object ball --point 0,0,2"), 1.0);
  // The camera flying at 0.6c straight toward the point: sqrt((1 + 0.6) / (1 - 0.6)) = 2.
  const std::string toward = " --set 'camera.velocity=[0,0,-0.6]'";
  EXPECT_NEAR(doppler("--world-point 0,0,-10" + toward), std::sqrt(1.6 / 0.4), 1e-9);
  EXPECT_NEAR(doppler("--world-point 0,0,-10" + toward), 2, 1e-9);
  // Flying away: 1/2. Across the light's path in W (n . beta = 0): gamma = 1.25, the
  // transverse Doppler effect.
  EXPECT_NEAR(doppler("--world-point 0,0,-10 --set 'camera.velocity=[0,0,0.6]'"), 0.5, 1e-9);
  EXPECT_NEAR(doppler("--world-point 0,0,-10 --set 'camera.velocity=[0.6,0,0]'"), 1.25, 1e-9);
  // The emitter approaching a camera at rest at 0.6c: 1 / (gamma (1 - 0.6)) = 2 as well.
  EXPECT_NEAR(doppler("--object ball --point 0,0,0 --set 'objects[0].velocity=[0,0,0.6]'"), 2,
              1e-9);
  // Without relativity there is no Doppler shift.
  EXPECT_EQ(doppler("--world-point 0,0,-10" + toward + " --set render.relativity=false"), 1.0);
  EXPECT_EQ(doppler("--object ball --point 0,0,0 --set 'objects[0].velocity=[0,0,0.6]'"
                    " --set render.relativity=false"),
            1.0);
}

// For --direction, "doppler" is the factor of the sky's light from that direction.
TEST_F(CliTest, LocateDopplerOfTheSkysLight) {
  const fs::path scene = write_scene(kScene);
  auto doppler = [&](const std::string& query) {
    const auto out = locate_output(locate(scene, query));
    return out.empty() ? -1.0 : out["doppler"].get<double>();
  };
  EXPECT_EQ(doppler("--direction 0,0,-1"), 1.0);
  // The camera flying at 0.6c toward the sky it looks at: 2; away from it: 1/2.
  EXPECT_NEAR(doppler("--direction 0,0,-1 --set 'camera.velocity=[0,0,-0.6]'"), 2, 1e-9);
  EXPECT_NEAR(doppler("--direction 0,0,-1 --set 'camera.velocity=[0,0,0.6]'"), 0.5, 1e-9);
  // Light crossing the camera's motion at a right angle in W: gamma = 1.25.
  EXPECT_NEAR(doppler("--direction 0,0,-1 --set 'camera.velocity=[0.6,0,0]'"), 1.25, 1e-9);
  // The sky itself approaching a camera at rest at 0.6c: 1 / (gamma (1 - 0.6)) = 2.
  EXPECT_NEAR(doppler("--direction 0,0,-1 --set 'sky.velocity=[0,0,0.6]'"), 2, 1e-9);
  EXPECT_EQ(doppler("--direction 0,0,-1 --set 'camera.velocity=[0,0,-0.6]'"
                    " --set render.relativity=false"),
            1.0);
}

// Visible points of the ball crossing at 0.8c are located on pixels drawn in the ball's colour.
TEST_F(CliTest, LocateObjectPointLandsOnTheRenderedBall) {
  const fs::path scene = write_scene(moving_black_ball());
  const CommandResult r = render(scene);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto image = read_png();
  EXPECT_EQ(png_byte(image->texel(0, 0).r), 255);  // the sky

  for (const char* point : {"0,0,2", "-2,0,0", "-1.2,0,1.6", "-1.6,1.2,0"}) {
    SCOPED_TRACE(point);
    const auto where = locate_output(locate(scene, std::string("--object ball --point ") + point));
    ASSERT_FALSE(where.empty());
    EXPECT_TRUE(where["in_view"].get<bool>());
    const int x = static_cast<int>(std::floor(at(where, "pixel", 0)));
    const int y = static_cast<int>(std::floor(at(where, "pixel", 1)));
    ASSERT_TRUE(x >= 0 && x < 64 && y >= 0 && y < 48) << x << "," << y;
    const Rgb c = image->texel(x, y);
    EXPECT_EQ(png_byte(c.r), 0) << x << "," << y;
    EXPECT_EQ(png_byte(c.g), 0) << x << "," << y;
    EXPECT_EQ(png_byte(c.b), 0) << x << "," << y;
    // The emission event lies on the camera's past light cone: |x| = -t.
    const double t = where["emission_time"].get<double>();
    const double d =
        std::hypot(at(where, "emission_position", 0), at(where, "emission_position", 1),
                   at(where, "emission_position", 2));
    EXPECT_NEAR(d, -t, 1e-9);
    EXPECT_NEAR(where["distance"].get<double>(), -t, 1e-9);  // the camera is at rest in W
  }
  // The front point's emission event is on its world-line: it left z = -8 when the ball's
  // centre was at x = 0.8 (t + 10). Light delay shows it well to the right of the image centre.
  const auto front = locate_output(locate(scene, "--object ball --point 0,0,2"));
  ASSERT_FALSE(front.empty());
  const double t = front["emission_time"].get<double>();
  EXPECT_NEAR(at(front, "emission_position", 0), 0.8 * (t + 10), 1e-9);
  EXPECT_NEAR(at(front, "emission_position", 1), 0, 1e-9);
  EXPECT_NEAR(at(front, "emission_position", 2), -8, 1e-9);
  EXPECT_GT(at(front, "pixel", 0), 42);
  // The centre's light left it at t = -10 from straight ahead.
  const auto centre = locate_output(locate(scene, "--object ball --point 0,0,0"));
  ASSERT_FALSE(centre.empty());
  EXPECT_NEAR(centre["emission_time"].get<double>(), -10, 1e-9);
  EXPECT_NEAR(at(centre, "pixel", 0), 32, 1e-9);
  EXPECT_NEAR(at(centre, "pixel", 1), 24, 1e-9);
}

// locate --pixel: what the render shows at a pixel. Each pixel of the moving ball's picture that
// is black is the ball, met on its surface at a point whose --point gives that pixel back; each
// red one is the sky. Its JSON has the contract's keys in order.
TEST_F(CliTest, LocatePixelSaysWhatThePictureShows) {
  const fs::path scene = write_scene(moving_black_ball());
  ASSERT_EQ(render(scene).status, 0);
  const auto image = read_png();
  int balls = 0, skies = 0;
  for (int y = 2; y < 48; y += 7)
    for (int x = 1; x < 64; x += 5) {
      SCOPED_TRACE(fmt::format("pixel {}, {}", x, y));
      const CommandResult r = locate(scene, fmt::format("--pixel {}.5,{}.5", x, y));
      ASSERT_EQ(r.status, 0) << r.err;
      const auto probe = nlohmann::ordered_json::parse(r.out);
      std::vector<std::string> keys;
      for (const auto& item : probe.items()) keys.push_back(item.key());
      EXPECT_EQ(keys, (std::vector<std::string>{"pixel", "direction", "meets", "object", "point",
                                                "sky", "disk", "emission_time", "emission_position",
                                                "emission_proper_time", "distance", "doppler"}));
      const bool black = png_byte(image->texel(x, y).r) == 0;
      if (probe["meets"] == "sky") {
        EXPECT_FALSE(black);
        EXPECT_TRUE(probe["emission_time"].is_null());
        ++skies;
        continue;
      }
      ASSERT_EQ(probe["meets"], "object");
      EXPECT_EQ(probe["object"], "ball");
      // (Pixels on the outline can go either way: their centre ray and the render's samples
      // differ.)
      const std::string point = fmt::format("{},{},{}", at(probe, "point", 0),
                                            at(probe, "point", 1), at(probe, "point", 2));
      const auto back = locate_output(locate(scene, "--object ball --point " + point));
      ASSERT_FALSE(back.empty());
      EXPECT_NEAR(at(back, "pixel", 0), x + 0.5, 1e-9);
      EXPECT_NEAR(at(back, "pixel", 1), y + 0.5, 1e-9);
      EXPECT_NEAR(back["emission_time"].get<double>(), probe["emission_time"].get<double>(), 1e-9);
      EXPECT_NEAR(back["doppler"].get<double>(), probe["doppler"].get<double>(), 1e-9);
      ++balls;
    }
  EXPECT_GT(balls, 10);
  EXPECT_GT(skies, 10);
}

TEST_F(CliTest, LocatePixelRefusesPointsOffThePicture) {
  const fs::path scene = write_scene(moving_black_ball());  // 64 x 48
  for (const char* pixel : {"64,1", "1,48", "-0.5,3"})
    expect_rejected(locate(scene, std::string("--pixel ") + pixel),
                    scene.string() + ": pixel: ", {"is not in the 64 x 48 picture"});
  expect_rejected(locate(scene, "--pixel 1,2,3"), "locate: pixel must be two numbers x, y, got 3");
  expect_rejected(locate(scene, "--pixel 1,2 --object ball"), "locate: pixel takes no object");
  expect_rejected(locate(scene, "--pixel 1,x"), "--pixel 1,x: expected numbers x,y");
}

// A big sphere at rest 1e7 away in direction d and the direction d itself land on the same
// pixel for a camera at 0.9c.
TEST_F(CliTest, LocateFarBodyAndDirectionAgree) {
  const double d[3] = {0.3, 0.1, -1};
  const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  char position[200];
  std::snprintf(position, sizeof position, "[%.17g, %.17g, %.17g]", 1e7 * d[0] / n, 1e7 * d[1] / n,
                1e7 * d[2] / n);
  const std::string far = edited(
      edited(edited(kScene, "{\"sphere\": {\"radius\": 2}}", "{\"sphere\": {\"radius\": 1000}}"),
             "\"position\": [0, 0, -10]", std::string("\"position\": ") + position),
      "\"name\": \"ball\"", "\"name\": \"far\"");
  // 0.9c along (0.2, 0.1, -1), so that the aberrated direction stays in view.
  const double v[3] = {0.2, 0.1, -1};
  const double k = 0.9 / std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  char velocity[200];
  std::snprintf(velocity, sizeof velocity, "[%.17g, %.17g, %.17g]", k * v[0], k * v[1], k * v[2]);
  const fs::path scene = write_scene(
      edited(far, "\n    \"velocity\": [0, 0, 0]", std::string("\n    \"velocity\": ") + velocity));
  const auto body = locate_output(locate(scene, "--object far --point 0,0,0"));
  const auto sky = locate_output(locate(scene, "--direction 0.3,0.1,-1"));
  ASSERT_FALSE(body.empty());
  ASSERT_FALSE(sky.empty());
  EXPECT_TRUE(sky["in_view"].get<bool>());
  EXPECT_EQ(body["in_view"], sky["in_view"]);
  EXPECT_NEAR(at(body, "pixel", 0), at(sky, "pixel", 0), 1e-3);
  EXPECT_NEAR(at(body, "pixel", 1), at(sky, "pixel", 1), 1e-3);
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_NEAR(at(body, "direction", i), at(sky, "direction", i), 1e-9);
  // Aberration moved it: at rest, the same direction is elsewhere in the image.
  const auto still =
      locate_output(locate(scene, "--direction 0.3,0.1,-1 --set 'camera.velocity=[0,0,0]'"));
  ASSERT_FALSE(still.empty());
  EXPECT_GT(std::abs(at(still, "pixel", 0) - at(sky, "pixel", 0)), 1.0);
}

TEST_F(CliTest, LocateBehindTheCameraHasNoPixel) {
  const fs::path scene = write_scene(kScene);
  const auto behind = locate_output(locate(scene, "--world-point 0,0,10"));
  EXPECT_TRUE(behind["pixel"].is_null());
  EXPECT_FALSE(behind["in_view"].get<bool>());
  const auto aside = locate_output(locate(scene, "--world-point 100,0,-10"));
  EXPECT_TRUE(aside["pixel"].is_null());
}

TEST_F(CliTest, AnAcceleratingCameraSeesWithItsVelocityAtItsProperTime) {
  // From rest, 0.5 along -z for 2 units of proper time, observed at proper time 1.5: the same
  // pictures and located directions as a camera at that event with that velocity
  // (tanh(0.75) = 0.63515) given directly.
  const std::string tail = R"(
  "objects": [{"name": "ball", "shape": {"sphere": {"radius": 1}}, "position": [2, 0, -8],
               "velocity": [0.3, 0, 0],
               "material": {"checker": {"size": 0.3, "colors": [[1, 0.5, 0], [0, 0.3, 1]]}}}],
  "sky": {"grid": {"spacing": 15}}
})";
  const fs::path accelerated = write_scene(R"({
  "camera": {"position": [0, 0, 0], "width": 96, "height": 64,
             "motion": {"phases": [{"duration": 2, "acceleration": [0, 0, -0.5]}]},
             "proper_time": 1.5},)" + tail,
                                           "accelerated.json");
  const double t = std::sinh(0.75) / 0.5, z = -(std::cosh(0.75) - 1) / 0.5;
  const fs::path inertial = write_scene(fmt::format(R"({{
  "camera": {{"position": [0, 0, {:.17g}], "time": {:.17g}, "velocity": [0, 0, {:.17g}],
             "width": 96, "height": 64}},)",
                                                    z, t, -std::tanh(0.75)) +
                                            tail,
                                        "inertial.json");
  for (const char* query :
       {"--direction 1,0.3,-1", "--direction -0.2,0.1,-1", "--object ball --point 0,1,0"}) {
    const auto a = locate_output(locate(accelerated, query));
    const auto b = locate_output(locate(inertial, query));
    ASSERT_FALSE(a.empty()) << query;
    for (const char* key : {"pixel", "direction"})
      for (std::size_t k = 0; k < a[key].size(); ++k)
        EXPECT_NEAR(a[key][k].get<double>(), b[key][k].get<double>(), 1e-9) << query << key;
    EXPECT_NEAR(a["doppler"].get<double>(), b["doppler"].get<double>(), 1e-12) << query;
  }
  // And the sky's direction is where the aberration formula puts it for the 4-velocity at that
  // proper time, (0, 0, -sinh(0.75)) / cosh(0.75).
  const Vec3 sky = normalize(Vec3{1, 0.3, -1});
  const Vec3 seen = aberrate_into_moving_frame(sky, {0, 0, -std::tanh(0.75)});
  const auto located = locate_output(locate(accelerated, "--direction 1,0.3,-1"));
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(located["direction"][k].get<double>(), seen[k], 1e-12) << k;
  const fs::path a_png = out_ / "a.exr", b_png = out_ / "b.exr";
  ASSERT_EQ(run_lightcone("render " + quoted(accelerated) + " -o " + quoted(a_png)).status, 0);
  ASSERT_EQ(run_lightcone("render " + quoted(inertial) + " -o " + quoted(b_png)).status, 0);
  EXPECT_LT(test::fraction_differing(*load_image_file(a_png), *load_image_file(b_png)), 0.001);
}

}  // namespace
}  // namespace lightcone
