// The real-time renderer against the ray tracer and against the C++ kernels: its GLSL
// functions on random inputs, its pictures of the bundled scenes, the tessellation of a pole
// bent by aberration and the principle of relativity. (What makes its frames fast, and its
// shaders as GLSL ES 3.00: tests/test_raster_speed.cpp.)
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "lightcone/color/colour_models.hpp"
#include "lightcone/frame/camera_model.hpp"
#include "lightcone/frame/emission.hpp"
#include "lightcone/frame/received_colour.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/frame/star_field.hpp"
#include "lightcone/io/image_file.hpp"
#include "lightcone/physics/doppler.hpp"
#include "lightcone/physics/light_path.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/physics/retarded_time.hpp"
#include "lightcone/raster/baseline_pass.hpp"
#include "lightcone/raster/frame_target.hpp"
#include "lightcone/raster/gl.hpp"
#include "lightcone/raster/gl_context.hpp"
#include "lightcone/raster/raster_renderer.hpp"
#include "lightcone/raster/shader_build.hpp"
#include "lightcone/raster/shader_sources.hpp"
#include "lightcone/raster/tessellation.hpp"
#include "lightcone/scene/reframe.hpp"
#include "lightcone/trace/renderer.hpp"
#include "support/glsl_eval.hpp"
#include "support/raster_agreement.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;
using test::agreement;
using test::Agreement;
using test::expect_agreement;
using test::quoted;

// ---------------------------------------------------------------------------------------------
// The GLSL functions against the C++ kernels, through transform feedback.

class GlslKernels : public testing::Test {
 protected:
  HeadlessGlContext context_;
  std::mt19937 rng_{5};
  std::uniform_real_distribution<double> u_{-1, 1};

  Vec3 random_vector(double scale) { return Vec3{u_(rng_), u_(rng_), u_(rng_)} * scale; }
  Vec3 random_velocity() {
    Vec3 v;
    do v = random_vector(1);
    while (length(v) >= 1 || length(v) < 1e-3);
    return v * (0.99 * std::abs(u_(rng_)) / length(v) + 1e-3);
  }
  static std::array<float, 9> pack(const Vec3& a, const Vec3& b, const Vec3& c) {
    return {float(a.x), float(a.y), float(a.z), float(b.x), float(b.y),
            float(b.z), float(c.x), float(c.y), float(c.z)};
  }
  // The inputs as the GPU holds them: the double kernels are given the same float values.
  static Vec3 as_float(const Vec3& v) { return {float(v.x), float(v.y), float(v.z)}; }
};

TEST_F(GlslKernels, RetardedEventMatchesMeetWorldLineToOnePartIn1e5) {
  std::vector<std::array<float, 9>> inputs;
  std::vector<TraceWorldLine> lines;
  std::vector<double> ray_times;
  for (int i = 0; i < 2000; ++i) {
    const TraceWorldLine line{as_float(random_vector(std::pow(10.0, 3 * u_(rng_)))),
                              as_float(random_velocity())};
    const double ray_time = i % 10 == 0 ? 0.0 : -1.0;
    lines.push_back(line);
    ray_times.push_back(ray_time);
    inputs.push_back(pack(line.position_at_zero, line.velocity,
                          {1 - dot(line.velocity, line.velocity), ray_time, 0}));
  }
  const auto out = evaluate_glsl("meet_world_line(c.y, a, b, c.x)", inputs);
  double worst = 0;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const RayEvent want = meet_world_line(ray_times[i], lines[i]);
    const double scale = want.s;
    const double error =
        std::max({std::abs(out[i][3] - want.s), std::abs(out[i][0] - want.position.x),
                  std::abs(out[i][1] - want.position.y), std::abs(out[i][2] - want.position.z)}) /
        scale;
    worst = std::max(worst, error);
  }
  EXPECT_LE(worst, 1e-5);
  // The kernel the shader mirrors is the closed form itself.
  const auto delays = evaluate_glsl("vec4(retarded_delay(a, b, c.x))", inputs);
  for (std::size_t i = 0; i < delays.size(); ++i) {
    const double want = retarded_delay(lines[i].position_at_zero, lines[i].velocity);
    EXPECT_NEAR(delays[i][0], want, 1e-5 * want) << i;
  }
}

// The stars' pixel filter in star_filter.glsl is frame/star_field.cpp's, over and past its
// support.
TEST_F(GlslKernels, StarFilterMatchesTheTracers) {
  std::vector<std::array<float, 9>> inputs;
  for (double dx = -1.75; dx <= 1.75; dx += 0.125)
    for (double dy = -1.75; dy <= 1.75; dy += 0.25)
      inputs.push_back({static_cast<float>(dx), static_cast<float>(dy), 0, 0, 0, 0, 0, 0, 0});
  const auto out =
      evaluate_glsl("vec4(star_filter_weight(a.xy))", inputs, shader_sources::star_filter_glsl);
  for (std::size_t i = 0; i < out.size(); ++i)
    EXPECT_NEAR(out[i][0], star_filter_weight(inputs[i][0], inputs[i][1]), 1e-7) << i;
}

// The hue model (common.glsl's hue_shift, with integrated_searchlight) against the C++ law on
// random colours and factors over five doublings either way, fading and looping, with greys,
// single primaries and ties between channels among them.
TEST_F(GlslKernels, HueShiftMatchesTheColourModel) {
  std::vector<std::array<float, 9>> inputs;
  std::uniform_real_distribution<double> unit(0, 1);
  for (int i = 0; i < 4000; ++i) {
    LinearRgb c{unit(rng_), unit(rng_), unit(rng_)};
    if (i % 7 == 0) c.g = c.r;             // a tie
    if (i % 11 == 0) c = {c.r, c.r, c.r};  // a grey
    if (i % 13 == 0) c = {0, 0, c.b};      // a primary
    const double d = std::exp2(5 * u_(rng_));
    const int loop = i % 2, model = i % 3;
    inputs.push_back(
        {float(c.r), float(c.g), float(c.b), float(d), float(loop), float(model), 0, 0, 0});
  }
  const auto out = evaluate_glsl(
      "vec4(hue_shift(a, b.x, b.y > 0.5) * integrated_searchlight(b.x, int(b.z)), 0.0)", inputs);
  double worst = 0;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const auto& in = inputs[i];
    const double d = in[3];
    const LinearRgb want = hue_shift({in[0], in[1], in[2]}, d, in[4] > 0.5);
    const double k = integrated_searchlight(d, in[5] == 0   ? SearchlightModel::kPhysical
                                               : in[5] == 1 ? SearchlightModel::kChang1996
                                                            : SearchlightModel::kOff);
    const double scale = std::max({want.r, want.g, want.b, 1e-3}) * k;
    const double error =
        std::max({std::abs(out[i][0] - want.r * k), std::abs(out[i][1] - want.g * k),
                  std::abs(out[i][2] - want.b * k)}) /
        scale;
    worst = std::max(worst, error);
  }
  EXPECT_LE(worst, 1e-4);
  std::printf("hue shift: worst relative error %.2g\n", worst);
}

TEST_F(GlslKernels, DopplerFactorMatchesTheFourVectorFormWithinItsConditionNumber) {
  // D = 1 / (gamma (1 + beta.u)): in single precision 1 + beta.u loses digits when the body
  // comes straight at the camera, so the bound grows with |beta.u| / (1 + beta.u).
  std::vector<std::array<float, 9>> inputs;
  std::vector<std::pair<Vec3, Vec3>> cases;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 look = as_float(normalize(random_vector(1)));
    const Vec3 beta = as_float(random_velocity());
    cases.push_back({look, beta});
    inputs.push_back(pack(look, beta, {lorentz_gamma(beta), 0, 0}));
  }
  const auto out = evaluate_glsl("vec4(doppler_factor(a, b, c.x))", inputs);
  int beyond_1e5 = 0;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const auto& [look, beta] = cases[i];
    const double want = doppler_factor(look * -1.0, beta, {});
    const double condition = std::abs(dot(beta, look)) / (1 + dot(beta, look));
    EXPECT_NEAR(out[i][0], want, 2e-6 * (1 + condition) * want) << i;
    beyond_1e5 += std::abs(out[i][0] - want) > 1e-5 * want;
  }
  EXPECT_LE(beyond_1e5, 20);  // only bodies coming almost straight at the camera
}

TEST_F(GlslKernels, SkyAberrationAndSearchlightMatchTheirKernels) {
  // The sky's direction through the resolved scene's own map, for cameras and skies in motion.
  for (int trial = 0; trial < 20; ++trial) {
    Scene scene;
    scene.camera.world_line.velocity = random_velocity();
    scene.camera.forward = normalize(random_vector(1));
    scene.camera.up = normalize(cross(scene.camera.forward, random_vector(1)));
    scene.camera.fov_degrees = 20 + 7 * trial;
    scene.sky.velocity = random_velocity() * 0.5;
    scene.render.light_delay = trial % 4 != 0;
    const ResolvedScene resolved = resolve_scene(scene);
    const Mat3& m = resolved.sky_spatial;
    std::vector<std::array<float, 9>> inputs;
    std::vector<Vec3> looks;
    for (int i = 0; i < 50; ++i) {
      looks.push_back(as_float(normalize(random_vector(1))));
      inputs.push_back(pack(looks.back(), resolved.sky_time_column, {resolved.ray_time, 0, 0}));
    }
    const std::string matrix = fmt::format("mat3({}, {}, {}, {}, {}, {}, {}, {}, {})", m.m[0][0],
                                           m.m[1][0], m.m[2][0], m.m[0][1], m.m[1][1], m.m[2][1],
                                           m.m[0][2], m.m[1][2], m.m[2][2]);  // column by column
    const auto out = evaluate_glsl("vec4(sky_direction(a, b, " + matrix + ", c.x), 0.0)", inputs);
    for (std::size_t i = 0; i < out.size(); ++i) {
      const Vec3 want = resolved.sky_direction(looks[i]);
      const double condition =
          lorentz_gamma(scene.camera.world_line.velocity) * lorentz_gamma(scene.sky.velocity) * 4;
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(out[i][k], want[k], 2e-6 * condition) << trial << " " << i;
    }
  }
  // The spectral searchlight factors.
  std::vector<std::array<float, 9>> inputs;
  for (int i = 0; i < 200; ++i) {
    const double d = std::exp(2 * u_(rng_));
    inputs.push_back(pack({d, 0, 0}, {0, 0, 0}, {0, 0, 0}));
  }
  for (int model = 0; model < 3; ++model) {
    const auto out =
        evaluate_glsl("vec4(spectral_searchlight(a.x, " + std::to_string(model) + "))", inputs);
    const SearchlightModel models[] = {SearchlightModel::kPhysical, SearchlightModel::kChang1996,
                                       SearchlightModel::kOff};
    for (std::size_t i = 0; i < out.size(); ++i) {
      const double want = spectral_searchlight(inputs[i][0], models[model]);
      EXPECT_NEAR(out[i][0], want, 1e-6 * want) << model << " " << i;
    }
  }
}

TEST_F(GlslKernels, ReceiveLegMatchesTheFourMomentumKernel) {
  // Random emission and reception events and velocities: the light leg's Doppler factor,
  // distance and directions.
  std::vector<std::array<float, 9>> inputs;
  struct Case {
    Vec4 separation;
    Vec3 beta_e, beta_r;
  };
  std::vector<Case> cases;
  for (int i = 0; i < 1000; ++i) {
    const Vec3 x = as_float(random_vector(20));
    // A null separation (the exact surface delay): reception - emission = (|x|, x).
    const Case c{{length(x), x}, as_float(random_velocity()), as_float(random_velocity())};
    cases.push_back(c);
    inputs.push_back(pack(c.separation.x, c.beta_e, c.beta_r));
  }
  const std::string leg = "receive_leg(vec4(0.0), b, vec4(length(a), a), c)";
  const auto doppler =
      evaluate_glsl("vec4(" + leg + ".doppler, " + leg + ".distance, 0.0, 0.0)", inputs);
  const auto direction = evaluate_glsl("vec4(" + leg + ".direction, 0.0)", inputs);
  const auto emitted = evaluate_glsl("vec4(" + leg + ".emitted_direction, 0.0)", inputs);
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const ReceivedLeg want =
        receive_leg({0, {}}, cases[i].beta_e, cases[i].separation, cases[i].beta_r);
    const double condition = 1 / (1 - length(cases[i].beta_e)) + 1 / (1 - length(cases[i].beta_r));
    EXPECT_NEAR(doppler[i][0], want.doppler, 2e-6 * condition * want.doppler) << i;
    EXPECT_NEAR(doppler[i][1], want.distance, 2e-6 * condition * want.distance) << i;
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(direction[i][k], want.direction[k], 2e-6 * condition) << i;
      EXPECT_NEAR(emitted[i][k], want.emitted_direction[k], 2e-6 * condition) << i;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Agreement with the ray tracer (support/raster_agreement.hpp).

TEST(RasterAgreement, BundledScenesMatchTheRayTracerOffTheSilhouettes) {
  for (const char* scene : {"terrell.json", "cubes.json", "sky.json", "street.json"})
    expect_agreement(scene, "--tessellation cpu");
}

// Accelerated and keyframed bodies and cameras, blinking lamps and clocks (their patterns run on
// each body's proper time, per fragment), a slow speed of light, a spinning wheel (each vertex
// on its own turning world-line, each fragment on the ray's curved path through the shape).
TEST(RasterAgreement, MovingClocksAndASpinningWheelMatchTheRayTracer) {
  for (const char* scene : {"rocket.json", "twin-paradox.json", "slow-light.json", "wheel.json"})
    expect_agreement(scene, "--tessellation cpu");
}

// Objects on accelerated and keyframed world-lines (both renderers draw each on its tangent
// world-line), their clocks and blinks per fragment, lit and unlit; spinning bodies, lit and
// unlit, a box, a round ball and a flattened one.
TEST(RasterAgreement, AcceleratedKeyframedAndSpinningBodiesMatchTheRayTracer) {
  const fs::path dir = test::fresh_temp_dir("raster-motion");
  test::write_text(dir / "scene.json", R"({
  "camera": {"position": [0, 1, 2.5], "time": 6, "velocity": [0.2, 0, -0.3], "fov": 70},
  "objects": [
    {"name": "rocket", "shape": {"box": {"size": [1.6, 1.2, 0.2]}}, "position": [-2.5, 1, -1],
     "velocity": [0.3, 0, 0], "motion": {"phases": [{"duration": 3, "acceleration": [0.004, 0.003, 0]},
                                                     {"duration": 4, "acceleration": [-0.002, 0, 0.003]}]},
     "material": {"clock": {"period": 3, "colors": [[0.9, 0.9, 0.8], [0.1, 0.1, 0.2]]}}},
    {"name": "drone", "shape": {"sphere": {"radius": 0.15}},
     "motion": {"keyframes": [{"time": 0, "position": [2, 0.5, -3]}, {"time": 3, "position": [2.3, 0.8, -2.8]},
                              {"time": 6, "position": [2.4, 1.0, -3]}]},
     "material": {"blink": {"period": 1, "duty": 0.4, "colors": [[0.2, 0.3, 0.8], [1, 0.8, 0.2]]}}},
    {"name": "lamp", "shape": {"box": {"size": [1, 1, 1]}}, "position": [0, 0.5, -3],
     "velocity": [0, 0, 0.4], "material": {"blink": {"period": 0.7, "colors": [[0.1, 0.1, 0.1], [0.9, 0.9, 0.9]]}, "unlit": false}},
    {"name": "floor", "shape": {"plane": {"size": [30, 30]}}, "position": [0, -0.5, -4],
     "material": {"checker": {"size": 1, "colors": [[0.4, 0.4, 0.45], [0.6, 0.6, 0.65]]}}},
    {"name": "top", "shape": {"box": {"size": [1.2, 0.8, 0.8]}}, "position": [1.6, 2.2, -2],
     "velocity": [-0.3, 0, 0], "spin": {"axis": [0.2, 1, 0.3], "rate": -30},
     "material": {"checker": {"size": 0.3, "colors": [[0.9, 0.5, 0.2], [0.9, 0.9, 0.9]]}, "unlit": false}},
    {"name": "ball", "shape": {"sphere": {"radius": 0.6}}, "position": [-1.2, 2.3, -2.5],
     "spin": {"axis": [0, 1, 0], "rate": 50},
     "material": {"checker": {"size": 0.25, "colors": [[0.2, 0.8, 0.4], [0.95, 0.95, 0.95]]}}},
    {"name": "lens", "shape": {"sphere": {"radius": 0.5}}, "scale": [1, 0.5, 1], "position": [0, 2.6, -3],
     "spin": {"axis": [1, 0, 0], "rate": 40},
     "material": {"checker": {"size": 0.2, "colors": [[0.8, 0.2, 0.6], [0.95, 0.95, 0.95]]}}}
  ],
  "lights": [{"name": "sun", "type": "directional", "direction": [0.3, -1, -0.4], "irradiance": 2}],
  "sky": {"grid": {}},
  "render": {"searchlight": "off"}
})");
  const Agreement a = agreement((dir / "scene.json").string(), 4, "--set render.shadows=false");
  EXPECT_GE(a.within, 0.99) << a.compared << " pixels compared";
  EXPECT_GT(a.compared, 640u * 360u / 2);
  EXPECT_EQ(a.raster_err, "");
  std::printf("moving clocks: %.4f of %zu pixels within 4/255\n", a.within, a.compared);
  fs::remove_all(dir);
}

// Motion blur: pass k is seen from the observation event of the ray tracer's sample k.
TEST(RasterAgreement, MotionBlurMatchesTheRayTracer) {
  expect_agreement("terrell.json", "--tessellation cpu --set camera.shutter=1.5");
}

// The same with the edges cut by tessellation shaders (OpenGL 4; llvmpipe has them).
TEST(RasterAgreement, TessellatedOnTheGpuTooTheyMatch) {
  for (const char* scene : {"terrell.json", "cubes.json", "street.json"})
    expect_agreement(scene, "--tessellation gpu");
  expect_agreement("street-lit.json", "--tessellation gpu --set render.shadows=false", 4);
}

// ---------------------------------------------------------------------------------------------
// Tessellation: a straight pole beside a camera moving sideways is seen bent.

Scene pole_scene() {
  Scene s;
  s.camera.width = 1280;
  s.camera.height = 720;
  s.camera.samples = 4;
  s.camera.fov_degrees = 90;
  s.camera.world_line.velocity = {0.9, 0, 0};
  s.render.doppler = DopplerModel::kOff;
  s.render.searchlight = SearchlightModel::kOff;
  Material red;
  red.pattern = SolidColor{{1, 0, 0}};
  // 10 units tall and 0.1 thick, 3 to the side of the camera's path and 2 ahead.
  s.objects.push_back(test::make_object("pole", Box{{0.1, 10, 0.1}}, {-1.5, 0, -2}, {}, red));
  s.sky.pattern = SolidColor{{0, 0, 0}};
  return s;
}

// The pole's centre in each image row (its coverage-weighted column), where it covers at
// least half a pixel of the row.
std::vector<std::pair<int, double>> pole_centres(const Image& image) {
  std::vector<std::pair<int, double>> centres;
  for (int y = 0; y < image.height; ++y) {
    double cover = 0, moment = 0;
    for (int x = 0; x < image.width; ++x) {
      const double r = std::clamp(image.texel(x, y).r, 0.0f, 1.0f);
      cover += r;
      moment += r * (x + 0.5);
    }
    if (cover >= 0.5) centres.push_back({y, moment / cover});
  }
  return centres;
}

// The largest difference in the pole's centre over the rows both images show it in.
double worst_offset(const Image& a, const Image& b) {
  const auto ca = pole_centres(a), cb = pole_centres(b);
  double worst = 0;
  std::size_t j = 0;
  for (const auto& [y, x] : ca) {
    while (j < cb.size() && cb[j].first < y) ++j;
    if (j < cb.size() && cb[j].first == y) worst = std::max(worst, std::abs(x - cb[j].second));
  }
  return worst;
}

TEST(RasterTessellation, ABentPoleStaysWithinAPixelOfTheRayTracersOutline) {
  const Scene scene = pole_scene();
  const Image traced = render_image(scene, RenderOptions{});
  const auto centres = pole_centres(traced);
  ASSERT_GT(centres.size(), 300u);
  // It is bent: the middle row's centre lies far off the line between the ends.
  const auto& [y0, x0] = centres.front();
  const auto& [y1, x1] = centres.back();
  double bend = 0;
  for (const auto& [y, x] : centres)
    bend = std::max(bend, std::abs(x - (x0 + (x1 - x0) * (y - y0) / double(y1 - y0))));
  EXPECT_GT(bend, 100);
  std::printf("the pole bends by %.0f px; tracer rows %zu\n", bend, centres.size());

  RasterStats stats;
  const Image adaptive = render_raster(scene, &stats, {}, 0, RasterTessellation::kCpu);
  EXPECT_EQ(pole_centres(adaptive).size(), centres.size());
  EXPECT_LE(worst_offset(traced, adaptive), 1.0);
  // Without adaptive tessellation (the box's faces split only as they are at load), it fails.
  TessellationLimits none;
  none.max_level = 0;
  const Image fixed = render_raster(scene, nullptr, none, 0, RasterTessellation::kCpu);
  EXPECT_TRUE(worst_offset(traced, fixed) > 1.0 || pole_centres(fixed).size() != centres.size());
  // Cut on the GPU, in equal pieces: within a pixel too, and not without the cuts.
  const Image gpu = render_raster(scene, nullptr, {}, 0, RasterTessellation::kGpu);
  EXPECT_EQ(pole_centres(gpu).size(), centres.size());
  EXPECT_LE(worst_offset(traced, gpu), 1.0);
  const Image gpu_fixed = render_raster(scene, nullptr, none, 0, RasterTessellation::kGpu);
  EXPECT_TRUE(worst_offset(traced, gpu_fixed) > 1.0 ||
              pole_centres(gpu_fixed).size() != centres.size());
  std::printf("worst offset cut on the GPU: %.3f px\n", worst_offset(traced, gpu));
  std::printf("worst offset: adaptive %.3f px (%zu triangles), without %.3f px\n",
              worst_offset(traced, adaptive), stats.triangles, worst_offset(traced, fixed));
}

// ---------------------------------------------------------------------------------------------
// The principle of relativity: one scene described in two frames, one picture.

// A mesh face's texture coordinates as an affine map of the shape point: the corners' own at the
// corners, and at any point of the face the barycentric interpolation the ray tracer does, with
// the barycentric coordinates found here independently (Cramer's rule on the face's edges).
TEST(RasterTessellation, AFacesTextureMapIsTheBarycentricInterpolation) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> any(-3, 3), unit(0, 1);
  for (int trial = 0; trial < 200; ++trial) {
    const std::array<Vec3, 3> corners = {Vec3{any(rng), any(rng), any(rng)},
                                         Vec3{any(rng), any(rng), any(rng)},
                                         Vec3{any(rng), any(rng), any(rng)}};
    std::array<std::array<float, 2>, 3> uvs;
    for (auto& uv : uvs) uv = {static_cast<float>(unit(rng)), static_cast<float>(unit(rng))};
    const std::array<double, 8> map = triangle_uv_map(corners, uvs);
    const auto uv_at = [&map](const Vec3& p, int k) {
      return map[4 * k] * p.x + map[4 * k + 1] * p.y + map[4 * k + 2] * p.z + map[4 * k + 3];
    };
    double b1 = unit(rng), b2 = unit(rng);
    if (b1 + b2 > 1) b1 = 1 - b1, b2 = 1 - b2;
    const Vec3 e1 = corners[1] - corners[0], e2 = corners[2] - corners[0];
    const Vec3 p = corners[0] + e1 * b1 + e2 * b2;
    // The barycentric coordinates again from p, by Cramer's rule in the face's plane.
    const Vec3 n = cross(e1, e2), q = p - corners[0];
    const double u = dot(cross(q, e2), n) / dot(n, n), v = dot(cross(e1, q), n) / dot(n, n);
    for (int k = 0; k < 2; ++k) {
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(uv_at(corners[c], k), uvs[c][k], 1e-9);
      EXPECT_NEAR(uv_at(p, k), uvs[0][k] * (1 - u - v) + uvs[1][k] * u + uvs[2][k] * v, 1e-9);
      // A point off the face reads the coordinates of its projection onto the face's plane.
      EXPECT_NEAR(uv_at(p + n * 0.37, k), uv_at(p, k), 1e-9);
    }
  }
  // A degenerate face maps everything to (0, 0).
  const std::array<double, 8> flat =
      triangle_uv_map({Vec3{0, 0, 0}, Vec3{1, 1, 1}, Vec3{2, 2, 2}}, {{{0, 0}, {1, 0}, {0, 1}}});
  for (const double x : flat) EXPECT_EQ(x, 0.0);
}

// Each edge of a rest mesh is indexed once, and the mesh is known closed and turned outward only
// when every edge is met twice in opposite directions around a positive volume.
TEST(RasterTessellation, ClosedSurfacesAreKnownByTheirEdges) {
  for (const Shape& shape : {Shape{Sphere{0.7}}, Shape{Box{Vec3{1, 2, 3}}}}) {
    const RestMesh m = rest_mesh(shape);
    EXPECT_TRUE(m.closed_outward);
    // Each edge shared by two triangles (a box's faces meet at vertices of their own).
    EXPECT_EQ(2 * m.edges.size(), 3 * m.triangles.size());
    for (std::size_t t = 0; t < m.triangles.size(); ++t)
      for (int side = 0; side < 3; ++side) {
        const auto [a, b] = m.edges[m.triangle_edges[t][side]];
        const Vec3 &p = m.positions[m.triangles[t][side]],
                   &q = m.positions[m.triangles[t][(side + 1) % 3]];
        EXPECT_TRUE((m.positions[a] == p && m.positions[b] == q) ||
                    (m.positions[a] == q && m.positions[b] == p));
      }
  }
  EXPECT_FALSE(rest_mesh(Plane{4, 4}).closed_outward);
  // A tetrahedron turned outward; turned inward; with a face missing; with one face flipped.
  auto tetrahedron = std::make_shared<Mesh>();
  tetrahedron->positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  tetrahedron->triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  EXPECT_TRUE(rest_mesh(MeshShape{tetrahedron}).closed_outward);
  auto inward = std::make_shared<Mesh>(*tetrahedron);
  for (auto& t : inward->triangles) std::swap(t[1], t[2]);
  EXPECT_FALSE(rest_mesh(MeshShape{inward}).closed_outward);
  auto open = std::make_shared<Mesh>(*tetrahedron);
  open->triangles.pop_back();
  EXPECT_FALSE(rest_mesh(MeshShape{open}).closed_outward);
  auto unoriented = std::make_shared<Mesh>(*tetrahedron);
  std::swap(unoriented->triangles[3][1], unoriented->triangles[3][2]);
  EXPECT_FALSE(rest_mesh(MeshShape{unoriented}).closed_outward);
}

// The bound that leaves an edge whole without its midpoint (EdgeErrorBound) is never
// below the error the midpoint shows (edge_error_pixels), for random edges of bodies moving up
// to 0.99c in random directions, near and far, with light delay and without; that it is nearly
// the error itself at its tightest; and that it spares the midpoints of short, distant edges.
TEST(RasterTessellation, TheEdgeBoundIsNeverBelowTheMidpointsError) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1, 1), share(0, 1);
  const auto random_direction = [&] {
    for (;;) {
      const Vec3 v{unit(random), unit(random), unit(random)};
      if (dot(v, v) > 1e-3 && dot(v, v) <= 1) return normalize(v);
    }
  };
  std::size_t bounded = 0, spared = 0, short_far = 0;
  double worst = 0;  // the largest share of its bound an error reaches
  for (int body = 0; body < 400; ++body) {
    Scene s;
    s.camera.width = 640, s.camera.height = 360, s.camera.fov_degrees = 30 + 80 * share(random);
    s.camera.world_line.velocity = random_direction() * (0.9 * share(random));
    s.render.light_delay = body % 5 != 0;
    const double far = std::pow(10.0, 3 * share(random));  // 1 to 1000 away
    Object box =
        test::make_object("box", Box{{1, 1, 1}}, random_direction() * far + Vec3{0, 0, -far},
                          random_direction() * (0.99 * share(random)), Material{});
    box.rotation = Mat3::rotation(random_direction(), 3 * share(random));
    box.scale = {1 + 3 * share(random), 1 + 3 * share(random), 1 + 3 * share(random)};
    s.objects.push_back(box);
    const ResolvedScene resolved = resolve_scene(s);
    const BodyView view = body_view(resolved, resolved.bodies[0]);
    for (int edge = 0; edge < 50; ++edge) {
      const double size = std::pow(10.0, -3 + 3 * share(random));  // 0.001 to 1 of the box
      const Vec3 a = Vec3{unit(random), unit(random), unit(random)} * 0.5;
      const Vec3 b = a + random_direction() * size;
      const ApparentPoint pa = apparent_point(resolved, view, a),
                          pb = apparent_point(resolved, view, b),
                          pm = apparent_point(resolved, view, (a + b) * 0.5);
      const double bound = EdgeErrorBound(resolved, view)
                               .pixels(a, pa, length(pa.position), b, pb, length(pb.position));
      if (!std::isfinite(bound)) continue;
      ++bounded;
      const double error = edge_error_pixels(resolved.camera, pa, pb, pm);
      EXPECT_LE(error, bound * (1 + 1e-9) + 1e-9) << body << " " << edge;
      if (error > 0.01) worst = std::max(worst, error / bound);
      if (size < 0.01 && far > 30) {
        ++short_far;
        spared += bound < 0.5;
      }
    }
  }
  EXPECT_GT(bounded, 10000u);
  EXPECT_GT(worst, 0.9);  // at its tightest, the bound is the error itself
  EXPECT_GT(spared, short_far * 9 / 10);
}

// The rasteriser skips the faces a closed body turns from the camera (HiddenFaces): the picture
// is the ray tracer's for a moving box, the same box mirrored (its faces wound the other way),
// and a room seen from inside, where nothing may be skipped.
TEST(RasterTessellation, OnlyHiddenFacesAreSkipped) {
  Scene s;
  s.camera.width = 320, s.camera.height = 180, s.camera.fov_degrees = 70;
  const auto checker = [](double size, Rgb a, Rgb b) {
    Material m;
    m.pattern = Checker{size, {a, b}};
    return m;
  };
  for (const double mirror : {1.0, -1.0}) {
    Object box;
    box.name = mirror > 0 ? "box" : "mirrored";
    box.shape = Box{Vec3{1.2, 1, 0.8}};
    box.world_line.position = {mirror * 1.1 - 0.6, 0.1, -2.8};
    box.world_line.velocity = {0.4, 0, 0.3};
    box.scale = {mirror, 1, 1};
    box.rotation = Mat3::rotation({0.3, 1, 0.2}, 0.7);
    box.material = checker(0.21, {0.9, 0.5, 0.2}, {0.1, 0.3, 0.8});
    s.objects.push_back(box);
  }
  Object room;
  room.name = "room";
  room.shape = Box{Vec3{30, 20, 40}};
  room.material = checker(2.5, {0.5, 0.5, 0.5}, {0.2, 0.25, 0.2});
  s.objects.push_back(room);

  const ResolvedScene resolved = resolve_scene(s);
  const auto hidden = [&](std::size_t body) {
    return hidden_faces(rest_mesh(resolved.bodies[body].object->shape), resolved.bodies[body]);
  };
  EXPECT_EQ(hidden(0), HiddenFaces::kBack);
  EXPECT_EQ(hidden(1), HiddenFaces::kFront);
  EXPECT_EQ(hidden(2), HiddenFaces::kNone);

  const Image traced = render_image(s, RenderOptions{});
  const Image drawn = render_raster(s, nullptr, {}, 0, RasterTessellation::kCpu);
  std::size_t close = 0;
  for (std::size_t k = 0; k < traced.rgb.size(); k += 3) {
    float worst = 0;
    for (int c = 0; c < 3; ++c)
      worst = std::max(worst, std::abs(std::clamp(traced.rgb[k + c], 0.0f, 1.0f) -
                                       std::clamp(drawn.rgb[k + c], 0.0f, 1.0f)));
    close += worst <= 4.0f / 255;
  }
  // Off by more only along the boxes' outlines and the checkers' edges.
  EXPECT_GE(static_cast<double>(close) / (traced.rgb.size() / 3), 0.97);

  // The CPU tessellation leaves the hidden triangles out (no vertex is shaded for them): a box
  // seen from outside shows at most three faces, so at most half its triangles are kept, and
  // those turned each way together are all of them.
  for (std::size_t body = 0; body < 2; ++body) {
    const RestMesh mesh = rest_mesh(resolved.bodies[body].object->shape);
    const BodyView view = body_view(resolved, resolved.bodies[body]);
    std::vector<float> all, back, front;
    tessellate(resolved, view, mesh, TessellationLimits{}, all);
    tessellate(resolved, view, mesh, TessellationLimits{}, back, nullptr, HiddenFaces::kBack);
    tessellate(resolved, view, mesh, TessellationLimits{}, front, nullptr, HiddenFaces::kFront);
    const std::size_t kept = (hidden(body) == HiddenFaces::kBack ? back : front).size();
    EXPECT_GT(kept, 0u) << body;
    EXPECT_LE(kept, all.size() / 2) << body;
    EXPECT_EQ(back.size() + front.size(), all.size()) << body;
  }
}

// The automatic exposure finds the same subject in both renderers (the bodies moving relative
// to the camera: body.frag's alpha, the tracer's hits), so both expose a picture alike.
TEST(RasterExposure, BothRenderersExposeForTheSameSubject) {
  for (const char* name : {"terrell.json", "wheel.json"}) {
    SCOPED_TRACE(name);
    Scene scene = test::load_repository_scene(name);
    scene.render.auto_exposure = true;  // (wheel.json gives its own)
    scene.camera.width /= 4, scene.camera.height /= 4;
    RenderStats traced;
    RasterStats drawn;
    render_image(scene, {}, &traced);
    render_raster(scene, &drawn);
    EXPECT_NEAR(drawn.exposure, traced.exposure, 0.05);
  }
}

TEST(RasterRelativity, TheSameSceneFromAnotherFrameRendersTheSameImage) {
  Scene scene;
  scene.camera.width = 160;
  scene.camera.height = 100;
  scene.camera.fov_degrees = 70;
  scene.camera.world_line.position = {0, 0.5, 6};
  scene.camera.world_line.velocity = {0.2, -0.1, -0.5};
  Material checker;
  checker.pattern = Checker{0.3, {{1, 0.2, 0.1}, {0.1, 0.2, 1}}};
  Material solid;
  solid.pattern = SolidColor{{0.9, 0.9, 0.2}};
  scene.objects.push_back(
      test::make_object("sphere", Sphere{1.0}, {-1.5, 0.5, -2}, {0.7, 0, 0}, checker));
  scene.objects.push_back(
      test::make_object("box", Box{{1, 1.5, 0.8}}, {1.8, 0.3, -1}, {0, 0.35, 0.28}, solid));
  scene.objects.push_back(test::make_object("ground", Plane{20, 20}, {0, -1, -3}, {}, checker));
  scene.sky.pattern = SkyGrid{};
  scene.sky.velocity = {0.3, 0.1, 0.0};
  for (const Vec3 frame : {Vec3{0.4, -0.3, 0.5}, Vec3{-0.8, 0.1, 0.2}}) {
    const Scene other = describe_in_frame(scene, frame);
    ASSERT_GT(length(other.camera.world_line.velocity - scene.camera.world_line.velocity), 0.1);
    const Image a = render_raster(scene), b = render_raster(other);
    EXPECT_LT(test::fraction_differing(a, b), 0.003) << frame.x;
  }
}

}  // namespace
}  // namespace lightcone
