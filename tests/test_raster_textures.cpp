// The real-time renderer's textures against the ray tracer: textured spheres, boxes, meshes
// and planes in motion under a moving sky image, unlit and lit, in every colour model (the
// spectral fit of a lit texel against its C++ kernels); clocks on meshes; and the sky image read
// from its mip levels at one sample a pixel.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <utility>

#include "lightcone/color/doppler_table.hpp"
#include "lightcone/color/rgb_spectrum.hpp"
#include "lightcone/frame/emission.hpp"
#include "lightcone/frame/lighting.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/io/image_file.hpp"
#include "lightcone/raster/frame_target.hpp"
#include "lightcone/raster/gl_context.hpp"
#include "lightcone/raster/raster_renderer.hpp"
#include "lightcone/raster/spectral_albedo.hpp"
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

// lighting.glsl's spectral fit of a lit texel against its C++ kernels: rgb_to_sigmoid's
// reflectance at every 10 nm for random colours (greys, saturated and black among them), and
// the reflected colour (xyz_of_reflection_seen_with_doppler, as linear sRGB) under a 5000 K
// lamp and a coloured one, for random factors.
TEST(GlslSpectralAlbedo, FitAndReflectedColourMatchTheKernels) {
  const HeadlessGlContext context;
  Scene scene;
  for (const auto& [name, colour] :
       {std::pair{"warm", Rgb{1, 0.8f, 0.6f}}, std::pair{"green", Rgb{0.2f, 1, 0.3f}}}) {
    Light lamp;
    lamp.name = name;
    lamp.kind = PointLight{};
    lamp.spectrum.emission = colour;
    scene.lights.push_back(lamp);
  }
  scene.lights[0].spectrum.emission = Blackbody{5000};
  scene.objects.push_back(
      test::make_object("ground", Plane{10, 10}, {0, -1, 0}, {}, test::lit({0.5f, 0.5f, 0.5f})));
  scene.camera.world_line.velocity = {0, 0, -0.6};
  const ResolvedScene resolved = resolve_scene(scene);
  const Lighting lighting(resolved, nullptr);
  SpectralAlbedo tables;
  tables.prepare(lighting, scene.lights.size(), -3, 3);
  const std::string sources =
      "#define LIGHTCONE_SPECTRAL_TEXTURES 1\n" + std::string(shader_sources::lighting_glsl);
  const auto setup = [&tables](GLuint program) { tables.bind(program, kSpectralAlbedoUnit); };

  std::mt19937 rng(3);
  std::uniform_real_distribution<float> unit(0, 1);
  std::vector<LinearRgb> colours = {{0, 0, 0}, {1, 1, 1}, {0.5, 0.5, 0.5}, {1, 0, 0},
                                    {0, 1, 0}, {0, 0, 1}, {0.9, 0.1, 0.0}};
  while (colours.size() < 300) colours.push_back({unit(rng), unit(rng), unit(rng)});
  std::vector<std::array<float, 9>> inputs;
  for (const LinearRgb& c : colours)
    for (int w = 0; w <= 47; ++w)
      inputs.push_back({static_cast<float>(c.r), static_cast<float>(c.g), static_cast<float>(c.b),
                        360.0f + 10 * w, 0, 0, 0, 0, 0});
  const auto fitted =
      evaluate_glsl("vec4(reflectance_at(rgb_to_sigmoid(a), b.x))", inputs, sources, setup);
  double worst = 0;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    const LinearRgb& c = colours[i / 48];
    const double want = RgbAlbedoSpectrum::from_rgb(c)(inputs[i][3]);
    worst = std::max(worst, std::abs(fitted[i][0] - want));
  }
  EXPECT_LT(worst, 2e-5);
  std::printf("fitted reflectance: largest difference %.2g\n", worst);

  // The reflected colour, given the kernel's coefficients (texel_reflectance).
  std::uniform_real_distribution<double> log_factor(-0.8, 0.8);
  inputs.clear();
  struct Case {
    SigmoidPolynomial fit;
    int light;
    double d_camera, d_light;
  };
  std::vector<Case> cases;
  for (std::size_t i = 0; i < 200; ++i) {
    const Case c{rgb_to_sigmoid(colours[i % colours.size()]), static_cast<int>(i % 2),
                 std::exp(log_factor(rng)), std::exp(log_factor(rng))};
    cases.push_back(c);
    inputs.push_back({static_cast<float>(c.fit.c0), static_cast<float>(c.fit.c1),
                      static_cast<float>(c.fit.c2), static_cast<float>(c.light),
                      static_cast<float>(c.d_camera), static_cast<float>(c.d_light), 0, 0, 0});
  }
  const auto reflected =
      evaluate_glsl("vec4(texel_reflected_of(a, int(b.x), b.y, b.z), 0.0)", inputs,
                    sources +
                        "vec3 texel_reflected_of(vec3 fit, int l, float dc, float dl) {\n"
                        "  texel_reflectance = fit;\n  return texel_reflected(l, dc, dl);\n}\n",
                    setup);
  double worst_relative = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Case& c = cases[i];
    const auto light = [&](double lambda) { return lighting.light_spectral(c.light, lambda); };
    // The factors as the shader has them (single precision).
    const double dc = static_cast<float>(c.d_camera), dl = static_cast<float>(c.d_light);
    const LinearRgb want = linear_srgb_from_xyz(
        xyz_of_reflection_seen_with_doppler(RgbAlbedoSpectrum{c.fit}, light, dc, dl));
    const double scale = std::max({std::abs(want.r), std::abs(want.g), std::abs(want.b), 1e-3});
    for (int k = 0; k < 3; ++k) {
      const double w = k == 0 ? want.r : k == 1 ? want.g : want.b;
      worst_relative = std::max(worst_relative, std::abs(reflected[i][k] - w) / scale);
    }
  }
  EXPECT_LT(worst_relative, 1e-4);
  std::printf("reflected colour: largest difference %.2g of its largest channel\n", worst_relative);
}

// A viewer keeps the lights' spectra with the lights' tables while they cover the frame: after
// a frame from elsewhere, the next frame of lit textures under the spectral model is the one a
// fresh renderer draws, whether the camera moved a little (spectra kept) or fast enough to need
// wider ones.
TEST(RasterSpectralTextures, KeptSpectraDrawWhatFreshOnesDo) {
  const HeadlessGlContext context;
  Scene scene = test::load_repository_scene("texture-mapping.json");
  for (Object& o : scene.objects) o.material.unlit = false;
  Light lamp;
  lamp.name = "lamp";
  lamp.kind = PointLight{};
  lamp.world_line.position = scene.camera.world_line.position + Vec3{1, 2, 0};
  lamp.world_line.velocity = {0.3, 0, 0};
  lamp.intensity = 20;
  scene.lights.push_back(lamp);
  scene.camera.width = 160, scene.camera.height = 90;
  const auto draw = [](RasterRenderer& renderer, const Scene& frame) {
    const FloatTarget target(frame.camera.width, frame.camera.height);
    target.bind();
    const ResolvedScene resolved = resolve_scene(frame);
    const EmissionTable emission(resolved);
    renderer.prepare(resolved, emission, {}, /*on_gpu=*/false);
    renderer.pass(0.5, 0.5, nullptr);
    return target.read();
  };
  RasterRenderer kept;
  draw(kept, scene);
  for (const Vec3 velocity : {Vec3{0, 0, -0.05}, Vec3{0, 0, -0.9}}) {
    SCOPED_TRACE(velocity.z);
    Scene next = scene;
    next.camera.world_line.velocity = velocity;
    const Image again = draw(kept, next);
    RasterRenderer fresh_renderer;
    const Image fresh = draw(fresh_renderer, next);
    ASSERT_EQ(again.rgb.size(), fresh.rgb.size());
    const test::ValueDifference d = test::compare_values(again, fresh, 1e-5f);
    EXPECT_EQ(d.differing, 0u);
    EXPECT_GT(d.lit, fresh.rgb.size() / 10);
  }
}

// A clock on a mesh: its dial read at each face's texture coordinates, as the tracer does, on a
// square of two triangles at 0.6c and on a lit one at rest.
TEST(RasterAgreement, ClocksOnMeshesMatchTheRayTracer) {
  const fs::path dir = test::fresh_temp_dir("mesh-clocks");
  test::write_text(dir / "square.obj", R"(v -1 -1 0
v 1 -1 0
v 1 1 0
v -1 1 0
vt 0 0
vt 1 0
vt 1 1
vt 0 1
f 1/1 2/2 3/3
f 1/1 3/3 4/4
)");
  test::write_text(dir / "scene.json", R"({
  "camera": {"position": [0, 0, 6], "fov": 60},
  "objects": [
    {"name": "dial", "shape": {"mesh": {"file": "square.obj"}}, "position": [-1.5, 0.3, 0],
     "time": -6, "velocity": [0.6, 0, 0], "scale": [1.4, 1.4, 1.4],
     "material": {"clock": {"period": 10, "colors": [[1, 0.95, 0.8], [0.1, 0.1, 0.3]]}}},
    {"name": "lit-dial", "shape": {"mesh": {"file": "square.obj"}}, "position": [1.8, -0.2, -1],
     "material": {"clock": {"period": 4, "colors": [[0.9, 0.9, 0.8], [0.2, 0.2, 0.5]]},
                  "unlit": false}}
  ],
  "lights": [{"name": "lamp", "type": "point", "position": [1, 2, 3], "intensity": 20}],
  "sky": {"color": [0.05, 0.05, 0.08]}
})");
  // (The moving mesh would cast no shadow of the lamp here.)
  expect_agreement((dir / "scene.json").string(), "--set render.shadows=false", 16);
  fs::remove_all(dir);
}

// Textured emitters on a sphere, a box, a mesh and a plane, and a sky image, all in motion: the
// colour of every sample looked up per sample and combined from the white's and the emitter nodes'
// tables (spectral) or from the primaries (the other models).
TEST(RasterAgreement, TexturesAndSkyImagesMatchTheRayTracer) {
  const fs::path dir = test::fresh_temp_dir("textures");
  const auto image = [](int width, int height, auto colour) {
    Image im;
    im.width = width;
    im.height = height;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const Rgb c = colour(double(x) / width, double(y) / height);
        im.rgb.insert(im.rgb.end(), {c.r, c.g, c.b});
      }
    return im;
  };
  const Image texture = image(64, 32, [](double u, double v) {
    const bool cell = (int(u * 8) + int(v * 4)) % 2 == 0;
    return Rgb{float(0.2 + 0.7 * u), float(cell ? 0.8 : 0.2), float(0.9 - 0.6 * v)};
  });
  const Image sky = image(256, 128, [](double u, double v) {
    return Rgb{float(0.1 + 0.5 * u), float(0.3 * (1 - v)), float(0.2 + 0.6 * v * u)};
  });
  write_images(texture, texture, {{dir / "texture.exr", ImageFormat::kExr}});
  write_images(sky, sky, {{dir / "sky.exr", ImageFormat::kExr}});
  test::write_text(dir / "scene.json", R"({
  "camera": {"position": [0, 1, 6], "velocity": [0.3, 0, -0.4], "fov": 70},
  "objects": [
    {"name": "ball", "shape": {"sphere": {"radius": 1.3}}, "position": [-1.8, 1.2, 0],
     "velocity": [0.6, 0, 0], "material": {"texture": "texture.exr"}},
    {"name": "crate", "shape": {"box": {"size": [1.6, 1.6, 1.6]}}, "position": [2, 1, -1],
     "velocity": [0, 0.3, 0.4], "material": {"texture": "texture.exr"}},
    {"name": "pyramid", "shape": {"mesh": {"file": "pyramid.obj"}}, "position": [0.6, -0.4, 2.2],
     "scale": [2.2, 2.2, 2.2], "rotation": {"axis": [0, 1, 0], "degrees": 30},
     "velocity": [-0.5, 0, 0],
     "material": {"texture": "texture.exr"}},
    {"name": "floor", "shape": {"plane": {"size": [30, 30]}}, "position": [0, -0.5, -4],
     "material": {"texture": "texture.exr"}}
  ],
  "sky": {"image": "sky.exr", "velocity": [0, 0, 0.5]}
})");
  // A textured mesh in motion: a pyramid whose faces each take their own part of the texture,
  // read at the barycentric texture coordinates of each sample's exact surface point.
  test::write_text(dir / "pyramid.obj", R"(v -0.8 0 -0.8
v 0.8 0 -0.8
v 0.8 0 0.8
v -0.8 0 0.8
v 0 1.4 0
vt 0.05 0.9
vt 0.45 0.9
vt 0.25 0.1
vt 0.55 0.95
vt 0.95 0.6
vt 0.7 0.05
vt 0.1 0.4
vt 0.6 0.45
f 1/1 2/2 5/3
f 2/4 3/5 5/6
f 3/1 4/2 5/6
f 4/7 1/8 5/3
f 1/7 3/5 2/8
f 1/7 4/4 3/5
)");

  // The searchlight brightens most of the picture past white; without it every texture shows.
  // The last cuts the edges in tessellation shaders (the texture maps pass through them).
  for (const char* settings : {"", "--set render.searchlight=off",
                               "--set render.doppler=rgb3 --set render.searchlight=off",
                               "--set render.doppler=off --set render.searchlight=off",
                               "--set render.doppler=hue --set render.searchlight=off",
                               "--set render.doppler=hue --set render.hue.loop=true",
                               "--tessellation gpu --set render.searchlight=off"}) {
    const Agreement a = agreement((dir / "scene.json").string(), 16, settings);
    EXPECT_GE(a.within, 0.99) << settings << ": " << a.compared << " pixels compared";
    EXPECT_EQ(a.raster_err, "") << settings;
    std::printf("textures %s: %.4f of %zu pixels within 4/255\n", settings, a.within, a.compared);
  }
  // Lit textures: the same bodies under a lamp and a sun, each sample's albedo its texel, under
  // the spectral model fitted to a reflectance spectrum (without shadows: the moving mesh casts
  // none here).
  std::string lit = test::bytes_of(dir / "scene.json");
  const std::string unlit_texture = R"("texture": "texture.exr"})";
  for (std::size_t at = lit.find(unlit_texture); at != std::string::npos;
       at = lit.find(unlit_texture, at + 1))
    lit.replace(at, unlit_texture.size(), R"("texture": "texture.exr", "unlit": false})");
  lit.replace(
      lit.find(R"(  "sky":)"), 0,
      R"(  "lights": [{"name": "lamp", "type": "point", "position": [0, 6, 3], "intensity": 40},
    {"name": "sun", "type": "directional", "direction": [-0.3, -1, -0.4], "irradiance": 0.5}],
)");
  test::write_text(dir / "lit.json", lit);
  // Under the spectral model each sample's texel is fitted to a reflectance and its light
  // summed nanometre by nanometre in both renderers: 4 samples a pixel, for time.
  const std::pair<const char*, int> lit_cases[] = {
      {"--set render.doppler=rgb3", 16},
      {"--set render.doppler=off --set render.searchlight=off", 16},
      {"--set render.doppler=hue --set render.searchlight=off", 16},
      {"--set render.searchlight=off", 4}};  // spectral
  for (const auto& [settings, samples] : lit_cases) {
    const Agreement a = agreement((dir / "lit.json").string(), samples,
                                  std::string("--set render.shadows=false ") + settings);
    EXPECT_GE(a.within, 0.99) << settings << ": " << a.compared << " pixels compared";
    EXPECT_EQ(a.raster_err, "") << settings;
    std::printf("lit textures %s: %.4f of %zu pixels within 4/255\n", settings, a.within,
                a.compared);
  }
  fs::remove_all(dir);
}

// At one sample a pixel the sky image is read from the mip level each pixel's footprint needs:
// the sky crowded ahead by aberration comes out closer to a 64-sample reference than the
// ray tracer's own single point sample does.
TEST(RasterSky, MipMappedSkyAtOneSampleDoesNotAlias) {
  const fs::path dir = test::fresh_temp_dir("sky-mip");
  Image sky;
  sky.width = 1024;
  sky.height = 512;
  for (int y = 0; y < sky.height; ++y)
    for (int x = 0; x < sky.width; ++x) {
      const bool cell = ((x / 8) + (y / 8)) % 2 == 0;
      sky.rgb.insert(sky.rgb.end(), {cell ? 0.9f : 0.05f, cell ? 0.6f : 0.1f, 0.3f});
    }
  write_images(sky, sky, {{dir / "sky.exr", ImageFormat::kExr}});
  test::write_text(dir / "scene.json", R"({
  "camera": {"position": [0, 0, 0], "velocity": [0, 0, -0.95], "fov": 60, "width": 320,
             "height": 180},
  "objects": [],
  "sky": {"image": "sky.exr"},
  "render": {"doppler": "off", "searchlight": "off"}
})");
  const auto render = [&](const std::string& options, const std::string& name) {
    const auto r = test::run_lightcone("render " + quoted(dir / "scene.json") + " --quiet -o " +
                                       quoted(dir / name) + " " + options);
    EXPECT_EQ(r.status, 0) << r.err;
    return load_image_file(dir / name);
  };
  const auto reference = render("--samples 64", "reference.exr");
  const auto traced = render("--samples 1", "traced.exr");
  const auto rastered = render("--samples 1 --renderer raster", "rastered.exr");
  const auto error = [&](const Image& a) {
    double sum = 0;
    for (std::size_t i = 0; i < a.rgb.size(); ++i) sum += std::abs(a.rgb[i] - reference->rgb[i]);
    return sum / a.rgb.size();
  };
  std::printf("mean error against 64 samples: ray tracer at 1 sample %.4f, raster %.4f\n",
              error(*traced), error(*rastered));
  EXPECT_LT(error(*rastered), 0.6 * error(*traced));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace lightcone
