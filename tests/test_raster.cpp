// The real-time renderer against the ray tracer and against the C++ kernels: its GLSL
// functions on random inputs, its pictures of the bundled scenes, the tessellation of a pole
// bent by aberration, the principle of relativity, and its shaders as GLSL ES 3.00.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <variant>
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

// The pass-through baseline of bench/bench_raster.cpp draws the triangles the frame it mirrors
// drew, where the frame draws them: the pixels it covers are those where the frame (under a
// black sky) shows a body.
TEST(RasterBaseline, DrawsTheFramesTriangles) {
  Scene scene = test::load_repository_scene("street.json");
  scene.camera.width = 160, scene.camera.height = 90, scene.camera.samples = 1;
  scene.sky.pattern = SolidColor{{0, 0, 0}};
  const HeadlessGlContext context;
  RasterRenderer renderer;
  const FloatTarget target(160, 90);
  target.bind();
  const ResolvedScene resolved = resolve_scene(scene);
  const EmissionTable emission(resolved);
  const std::size_t triangles =
      renderer.prepare(resolved, emission, {}, /*on_gpu=*/false).triangles;
  ASSERT_GT(triangles, 1000u);
  const BaselinePass baseline;
  EXPECT_EQ(baseline.draw(resolved, renderer), triangles);
  const Image drawn = target.read();
  renderer.pass();
  const Image frame = target.read();
  std::size_t covered = 0, differ = 0;
  for (std::size_t p = 0; p < drawn.rgb.size() / 3; ++p) {
    const bool base = drawn.rgb[3 * p] == 1.0f;
    const bool body = frame.rgb[3 * p] + frame.rgb[3 * p + 1] + frame.rgb[3 * p + 2] > 0;
    covered += base;
    differ += base != body;
  }
  EXPECT_GT(covered, 160u * 90 / 10);  // the street's houses fill much of the view
  EXPECT_EQ(differ, 0u);
}

// RasterFloor (bench/bench_raster.cpp) is the frame with its bodies shaded for nothing: the
// baseline's bodies, and behind them the frame's own sky, drawn as the frame draws it.
TEST(RasterBaseline, FloorDrawsTheFramesSkyBehindTheBodies) {
  Scene scene = test::load_repository_scene("street.json");
  scene.camera.width = 160, scene.camera.height = 90, scene.camera.samples = 1;
  ASSERT_TRUE(std::holds_alternative<SkyGrid>(scene.sky.pattern));
  const HeadlessGlContext context;
  RasterRenderer renderer;
  const FloatTarget target(160, 90);
  target.bind();
  const ResolvedScene resolved = resolve_scene(scene);
  const EmissionTable emission(resolved);
  renderer.prepare(resolved, emission, {}, /*on_gpu=*/false);
  const BaselinePass baseline;
  baseline.draw(resolved, renderer);
  const Image bodies = target.read();
  renderer.sky_pass();
  const Image floor = target.read();
  renderer.pass();
  const Image frame = target.read();
  std::size_t sky = 0;
  for (std::size_t i = 0; i < floor.rgb.size(); ++i) {
    const bool body = bodies.rgb[i - i % 3] == 1.0f;
    sky += !body && i % 3 == 0;
    ASSERT_EQ(floor.rgb[i], body ? bodies.rgb[i] : frame.rgb[i]) << i;
  }
  EXPECT_GT(sky, 160u * 90 / 10);
}

// The colour rows are kept from frame to frame while they are the same rows over a range that
// covers the next frame's, as in the viewer, whose frames differ in the camera alone: each frame
// is drawn as a renderer drawing it first draws it (up to the nodes' interpolation), and the
// rows are tabulated anew where the camera's speed leaves their range or a setting changes.
// (The emission tables are kept over a wide range, so that the rows' own range decides.)
TEST(RasterKeptRows, EachFrameIsDrawnAsAFirstFrameIs) {
  for (const char* name : {"street.json", "street-lit.json"}) {
    SCOPED_TRACE(name);
    Scene scene = test::load_repository_scene(name);
    scene.camera.width = 160, scene.camera.height = 90, scene.camera.samples = 1;
    const HeadlessGlContext context;
    const FloatTarget target(160, 90);
    target.bind();
    RasterRenderer kept_renderer;
    std::unique_ptr<EmissionTable> kept_emission;
    const auto draw_kept = [&](bool& tabulated) {
      const ResolvedScene resolved = resolve_scene(scene);
      if (!kept_emission || !kept_emission->serves(resolved))
        kept_emission = std::make_unique<EmissionTable>(resolved, 2.0);
      tabulated =
          kept_renderer.prepare(resolved, *kept_emission, {}, /*on_gpu=*/false).rows_tabulated;
      kept_renderer.pass();
      return target.read();
    };
    const auto draw_first = [&] {
      RasterRenderer renderer;
      const ResolvedScene resolved = resolve_scene(scene);
      const EmissionTable emission(resolved);
      renderer.prepare(resolved, emission, {}, /*on_gpu=*/false);
      renderer.pass();
      return target.read();
    };
    struct Step {
      const char* change;
      std::function<void()> apply;
      bool tabulated;
    };
    const Vec3 velocity = scene.camera.world_line.velocity;
    for (const Step& step : {
             Step{"the first frame", [] {}, true},
             Step{"the camera a little ahead", [&] { scene.camera.world_line.position.z -= 0.5; },
                  false},
             Step{"the camera a little faster",
                  [&] { scene.camera.world_line.velocity = velocity * 1.01; }, false},
             Step{"the camera far faster",
                  [&] { scene.camera.world_line.velocity = velocity * (0.97 / length(velocity)); },
                  true},
             Step{"the searchlight off", [&] { scene.render.searchlight = SearchlightModel::kOff; },
                  true},
             Step{"the hue model", [&] { scene.render.doppler = DopplerModel::kHue; }, true},
         }) {
      SCOPED_TRACE(step.change);
      step.apply();
      bool tabulated = false;
      const Image kept = draw_kept(tabulated);
      EXPECT_EQ(tabulated, step.tabulated);
      const Image first = draw_first();
      const test::ValueDifference d = test::compare_values(kept, first, 1e-4f);
      EXPECT_EQ(d.differing, 0u);
      EXPECT_GT(d.lit, first.rgb.size() / 4);
    }
  }
}

// A frame's body programs hold only the features its bodies use (raster/shader_build.hpp,
// body_variant_defines); each such frame is drawn exactly as by the programs with every feature:
// street.json (none), the spinning wheel, the twin paradox's clocks, street-lit.json (lit; and
// with its towers moving, their shadows met exactly; and glossy under a sphere lamp and the sun),
// the wheel lit by a lamp (a spinning mesh's shadow met along its curve), the cubes with several
// samples a pixel (per-pixel shading offsets), a spot light (headlight.json) and a light moving
// relative to what it lights (interceptor.json).
TEST(RasterVariants, EachDrawsItsSceneAsTheFullProgramsDo) {
  const auto draw = [](const Scene& scene, bool specialise, bool offsets) {
    const HeadlessGlContext context;
    RasterRenderer renderer;
    renderer.set_specialised_programs(specialise);
    const FloatTarget target(scene.camera.width, scene.camera.height);
    target.bind();
    const ResolvedScene resolved = resolve_scene(scene);
    const EmissionTable emission(resolved);
    renderer.prepare(resolved, emission, {}, /*on_gpu=*/false);
    // Offsets: each pixel shaded at a point of its own (the second of four samples).
    std::vector<float> shading(4 * static_cast<std::size_t>(scene.camera.width) *
                               scene.camera.height);
    for (std::size_t i = 0; i < shading.size(); i += 4) {
      shading[i] = 0.3f + 0.4f * static_cast<float>((i / 4) % 7) / 7;
      shading[i + 1] = 0.6f;
      shading[i + 2] = shading[i + 3] = 0.5f;
    }
    renderer.pass(0.5, 0.5, offsets ? &shading : nullptr);
    return target.read();
  };
  struct Case {
    const char* scene;
    bool offsets;
    bool hue = false;
    bool lit_textures = false;       // its textures lit by a lamp (the spectral fit per sample)
    bool moving_meshes = false;      // its meshes moving relative to the lamps (met exactly)
    bool glossy_more_lamps = false;  // its lit bodies glossy, and a sphere lamp and the sun
  };
  for (const Case c :
       {Case{"street.json", false}, Case{"wheel.json", false}, Case{"twin-paradox.json", false},
        Case{"street-lit.json", false}, Case{"cubes.json", true},
        Case{"street-lit.json", false, true}, Case{"texture-mapping.json", false, false, true},
        Case{"street-lit.json", false, false, false, true}, Case{"wheel.json", false, false, true},
        Case{"headlight.json", false}, Case{"interceptor.json", false},
        Case{"street-lit.json", false, false, false, false, true}}) {
    SCOPED_TRACE(c.scene);
    Scene scene = test::load_repository_scene(c.scene);
    if (c.hue) scene.render.doppler = DopplerModel::kHue;
    if (c.moving_meshes)
      for (Object& o : scene.objects)
        if (std::holds_alternative<MeshShape>(o.shape)) o.world_line.velocity = {0, 0, 0.3};
    if (c.glossy_more_lamps) {
      for (Object& o : scene.objects) o.material.glossy = Glossy{0.4, 0.1};
      Light lamp;
      lamp.name = "sphere lamp";
      lamp.kind = SphereLight{0.5};
      lamp.world_line.position = scene.camera.world_line.position + Vec3{-2, 3, -6};
      lamp.intensity = 40;
      scene.lights.push_back(lamp);
      Light sun;
      sun.name = "sun";
      sun.kind = DirectionalLight{{0.3, -1, -0.4}, 0.5};
      scene.lights.push_back(sun);
    }
    if (c.lit_textures) {
      for (Object& o : scene.objects) o.material.unlit = false;
      Light lamp;
      lamp.name = "lamp";
      lamp.kind = PointLight{};
      lamp.world_line.position = scene.camera.world_line.position + Vec3{1, 2, 0};
      lamp.intensity = 20;
      scene.lights.push_back(lamp);
    }
    scene.camera.width = 160, scene.camera.height = 90;
    const Image specialised = draw(scene, true, c.offsets), full = draw(scene, false, c.offsets);
    ASSERT_EQ(specialised.rgb.size(), full.rgb.size());
    const test::ValueDifference d = test::compare_values(specialised, full, 1e-6f);
    EXPECT_EQ(d.differing, 0u);
    EXPECT_GT(d.lit, full.rgb.size() / 10);
  }
}

// ---------------------------------------------------------------------------------------------
// The shaders as GLSL ES 3.00 (WebGL 2): the same sources with only the version and precision
// lines changed, through the reference compiler.

TEST(RasterShaders, CompileAsGlslEs300) {
  const fs::path dir = test::fresh_temp_dir("glsl-es");
  struct Stage {
    const char* name;
    const char* source;
    bool fragment;
    const char* extra = "";    // what the program puts between the shared code and the stage
    const char* defines = "";  // which variant of the stage
  };
  const std::string patterns = shader_sources::patterns_glsl;
  const std::string lighting = shader_sources::lighting_glsl;
  const std::string stripped = body_variant_defines(0);
  const std::string stripped_textured = "#define LIGHTCONE_TEXTURED 1\n" + stripped;
  const std::string stripped_lit = "#define LIGHTCONE_LIT 1\n" + stripped;
  const std::string every_light = lighting_variant_defines(kAllLightingFeatures);
  const std::string patterns_and_hole = patterns + shader_sources::black_hole_glsl;
  const Stage stages[] = {
      {"body.vert", shader_sources::body_vert, false, shader_sources::body_projection_glsl},
      {"body-textured.vert", shader_sources::body_vert, false, shader_sources::body_projection_glsl,
       "#define LIGHTCONE_TEXTURED 1\n"},
      {"body.frag", shader_sources::body_frag, true, patterns.c_str()},
      {"body-textured.frag", shader_sources::body_frag, true, patterns.c_str(),
       "#define LIGHTCONE_TEXTURED 1\n"},
      {"body-lit.frag", shader_sources::body_frag, true, patterns.c_str(),
       "#define LIGHTCONE_LIT 1\n"},
      {"body-lit-textured.frag", shader_sources::body_frag, true, patterns.c_str(),
       "#define LIGHTCONE_LIT 1\n#define LIGHTCONE_LIT_TEXTURES 1\n"},
      {"body-lit-textured.vert", shader_sources::body_vert, false,
       shader_sources::body_projection_glsl, "#define LIGHTCONE_LIT_TEXTURES 1\n"},
      {"body-lit-textured-spectral.frag", shader_sources::body_frag, true, patterns.c_str(),
       "#define LIGHTCONE_LIT 1\n#define LIGHTCONE_LIT_TEXTURES 1\n"
       "#define LIGHTCONE_SPECTRAL_TEXTURES 1\n"},
      {"body-mesh-clocks.frag", shader_sources::body_frag, true, patterns.c_str(),
       "#define LIGHTCONE_MESH_CLOCKS 1\n"},
      {"lit_surfaces.frag", shader_sources::lit_surfaces_frag, true, lighting.c_str()},
      {"lit_surfaces-spectral-textures.frag", shader_sources::lit_surfaces_frag, true,
       lighting.c_str(), "#define LIGHTCONE_SPECTRAL_TEXTURES 1\n"},
      {"lit_surfaces-exact-shadows.frag", shader_sources::lit_surfaces_frag, true, lighting.c_str(),
       "#define LIGHTCONE_EXACT_SHADOWS 1\n"},
      {"lit_surfaces-mesh-shadows.frag", shader_sources::lit_surfaces_frag, true, lighting.c_str(),
       "#define LIGHTCONE_EXACT_SHADOWS 1\n#define LIGHTCONE_MESH_SHADOWS 1\n"},
      {"lit_surfaces-spin-shadows.frag", shader_sources::lit_surfaces_frag, true, lighting.c_str(),
       "#define LIGHTCONE_EXACT_SHADOWS 1\n#define LIGHTCONE_MESH_SHADOWS 1\n"
       "#define LIGHTCONE_SPIN_SHADOWS 1\n"},
      // Each with every feature a frame may leave out left out (body_variant_defines).
      {"body-specialised.frag", shader_sources::body_frag, true, patterns.c_str(),
       stripped.c_str()},
      {"body-textured-specialised.frag", shader_sources::body_frag, true, patterns.c_str(),
       stripped_textured.c_str()},
      {"body-lit-specialised.frag", shader_sources::body_frag, true, patterns.c_str(),
       stripped_lit.c_str()},
      {"lit_surfaces-specialised.frag", shader_sources::lit_surfaces_frag, true, lighting.c_str(),
       stripped.c_str()},
      {"lit_surfaces-every-light.frag", shader_sources::lit_surfaces_frag, true, lighting.c_str(),
       every_light.c_str()},
      {"lit_surfaces-spectral-model.frag", shader_sources::lit_surfaces_frag, true,
       lighting.c_str(), "#define LIGHTCONE_SPECTRAL_MODEL 1\n"},
      {"lit_surfaces-other-models.frag", shader_sources::lit_surfaces_frag, true, lighting.c_str(),
       "#define LIGHTCONE_OTHER_MODELS 1\n"},
      {"hole_body.vert", shader_sources::hole_body_vert, false,
       shader_sources::body_projection_glsl},
      {"hole_body.frag", shader_sources::hole_body_frag, true, patterns.c_str()},
      {"hole_body-disk.frag", shader_sources::hole_body_frag, true, patterns_and_hole.c_str(),
       "#define LIGHTCONE_DISK_HIDES_BODIES 1\n"},
      {"fullscreen.vert", shader_sources::fullscreen_vert, false},
      {"display.frag", shader_sources::display_frag, true, shader_sources::tone_map_glsl},
      {"sky.frag", shader_sources::sky_frag, true},
      {"sky-image.frag", shader_sources::sky_frag, true, "", "#define LIGHTCONE_SKY_IMAGE 1\n"},
      {"sky-hole.frag", shader_sources::sky_frag, true, shader_sources::black_hole_glsl,
       "#define LIGHTCONE_BLACK_HOLE 1\n"},
      {"sky-hole-image.frag", shader_sources::sky_frag, true, shader_sources::black_hole_glsl,
       "#define LIGHTCONE_BLACK_HOLE 1\n#define LIGHTCONE_SKY_IMAGE 1\n"},
      {"star.vert", shader_sources::star_vert, false, shader_sources::body_projection_glsl},
      {"baseline.vert", shader_sources::baseline_vert, false, shader_sources::body_projection_glsl},
      {"baseline.frag", shader_sources::baseline_frag, true},
      {"shadow.vert", shader_sources::shadow_vert, false, shader_sources::body_projection_glsl},
      {"shadow.frag", shader_sources::shadow_frag, true},
      {"star.frag", shader_sources::star_frag, true, shader_sources::star_filter_glsl}};
  for (const Stage& stage : stages) {
    const fs::path file = dir / stage.name;
    test::write_text(file, std::string("#version 300 es\nprecision highp float;\nprecision highp "
                                       "int;\nprecision highp sampler2D;\n") +
                               (stage.fragment ? "#define LIGHTCONE_FRAGMENT_STAGE 1\n" : "") +
                               stage.defines + shader_sources::common_glsl + stage.extra +
                               stage.source);
    const std::string command =
        "glslangValidator '" + file.string() + "' > '" + (dir / "log").string() + "' 2>&1";
    const int status = std::system(command.c_str());
    std::ifstream log(dir / "log");
    const std::string text((std::istreambuf_iterator<char>(log)), {});
    EXPECT_EQ(status, 0) << stage.name << ": " << text;
  }
  // The tessellation stages are OpenGL 4 only (WebGL 2 has none): checked as GLSL 400.
  const Stage tessellation_stages[] = {{"body.tesc", shader_sources::body_tesc, false},
                                       {"body.tese", shader_sources::body_tese, false},
                                       {"patch.vert", shader_sources::patch_vert, false}};
  for (const Stage& stage : tessellation_stages)
    for (const char* defines : {"", "#define LIGHTCONE_TEXTURED 1\n"}) {
      const fs::path file = dir / (std::string(*defines ? "textured-" : "") + stage.name);
      test::write_text(file, std::string("#version 400 core\n") + defines +
                                 shader_sources::common_glsl +
                                 shader_sources::body_projection_glsl + stage.source);
      const int status = std::system(
          ("glslangValidator '" + file.string() + "' > '" + (dir / "log").string() + "' 2>&1")
              .c_str());
      std::ifstream log(dir / "log");
      const std::string text((std::istreambuf_iterator<char>(log)), {});
      EXPECT_EQ(status, 0) << stage.name << ": " << text;
    }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lightcone
