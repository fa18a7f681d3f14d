// The same command gives the same bytes every run (issue 22): each renderer run three times on
// bundled scenes (one with motion blur, one with a light), the ray tracer on one, two, five and
// every thread, `animate` twice; and the rule that picks the raster renderer's tessellation path
// from the GL driver alone, never from timing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "lightcone/raster/gl_context.hpp"
#include "lightcone/raster/raster_renderer.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;
using test::bytes_of;
using test::quoted;
using test::run_lightcone;

bool have_gl() {
  try {
    const HeadlessGlContext context;
    return true;
  } catch (const GlUnavailable&) {
    return false;
  }
}

// A bundled scene and the settings it is run with (small, so that three runs stay quick).
struct Case {
  const char* scene;
  const char* settings;
};
const Case kCases[] = {
    {"terrell.json", ""},
    {"terrell.json", " --set camera.shutter=1.5"},  // motion blur: one observation a sample
    {"headlight.json", " --samples 2"},             // a moving spot light on a lit wall
};

class Determinism : public test::TempDirTest {
 protected:
  // Renders a case to a fresh EXR (linear radiance as floats: the strictest comparison) and
  // returns its bytes.
  std::string render(const Case& c, const std::string& options, const std::string& name) {
    const fs::path out = dir_ / (name + ".exr");
    const auto r = run_lightcone(
        "render " + quoted(fs::path(LIGHTCONE_SOURCE_DIR) / "scenes" / c.scene) + " -o " +
        quoted(out) + " --width 160 --height 90 --quiet " + options + c.settings);
    EXPECT_EQ(r.status, 0) << c.scene << " " << options << ": " << r.err;
    std::string bytes = bytes_of(out);
    EXPECT_FALSE(bytes.empty()) << c.scene << " " << options;
    return bytes;
  }

  // Three runs of one command give the same bytes.
  void expect_three_runs_alike(const std::string& options) {
    for (const Case& c : kCases) {
      const std::string first = render(c, options, "first");
      for (const char* again : {"second", "third"})
        EXPECT_TRUE(render(c, options, again) == first)
            << c.scene << c.settings << " " << options << ": run " << again << " differs";
    }
  }
};

TEST_F(Determinism, RayTracerGivesTheSameBytesEveryRun) {
  expect_three_runs_alike("--renderer trace");
}

TEST_F(Determinism, RayTracerGivesTheSameBytesOnAnyNumberOfThreads) {
  // The tiles are shared among the threads as they come free; the bytes must not depend on it.
  // interceptor.json adds shadow rays through the lights' labelled BVHs.
  std::vector<Case> cases(std::begin(kCases), std::end(kCases));
  cases.push_back({"interceptor.json", " --samples 2"});
  for (const Case& c : cases) {
    const std::string every = render(c, "--renderer trace", "every");
    EXPECT_TRUE(render(c, "--renderer trace --threads 1", "one") == every)
        << c.scene << c.settings << ": one thread";
    EXPECT_TRUE(render(c, "--renderer trace --threads 2", "two") == every)
        << c.scene << c.settings << ": two threads";
    EXPECT_TRUE(render(c, "--renderer trace --threads 5", "five") == every)
        << c.scene << c.settings << ": five threads";
  }
}

TEST_F(Determinism, RasterRendererGivesTheSameBytesEveryRun) {
  if (!have_gl()) GTEST_SKIP() << "no OpenGL 3.3 context";
  // The default tessellation (auto) and each path as asked.
  for (const char* tessellation : {"", " --tessellation cpu", " --tessellation gpu"})
    expect_three_runs_alike(std::string("--renderer raster") + tessellation);
}

TEST_F(Determinism, AnimateGivesTheSameFramesEveryRun) {
  const std::string rocket = quoted(fs::path(LIGHTCONE_SOURCE_DIR) / "scenes" / "rocket.json");
  std::vector<std::string> renderers = {"trace"};
  if (have_gl()) renderers.push_back("raster");
  for (const std::string& renderer : renderers)
    for (const char* run : {"a", "b"}) {
      const auto r =
          run_lightcone("animate " + rocket + " --fps 4 --frames 0-3 -o " +
                        quoted(dir_ / (renderer + run + "-%d.exr")) +
                        " --width 96 --height 54 --samples 2 --quiet --renderer " + renderer);
      ASSERT_EQ(r.status, 0) << renderer << ": " << r.err;
    }
  for (const std::string& renderer : renderers)
    for (int i = 0; i <= 3; ++i) {
      const std::string a = bytes_of(dir_ / (renderer + "a-" + std::to_string(i) + ".exr"));
      EXPECT_FALSE(a.empty()) << renderer << " frame " << i;
      EXPECT_TRUE(bytes_of(dir_ / (renderer + "b-" + std::to_string(i) + ".exr")) == a)
          << renderer << " frame " << i;
    }
}

TEST_F(Determinism, TheTwoTessellationPathsDifferSoAFlipBetweenThemIsCaught) {
  // Why `auto` must not time the paths: they draw different bytes (outlines cut differently),
  // so a choice that flipped from run to run would change the file; the tests above would see it.
  if (!have_gl()) GTEST_SKIP() << "no OpenGL 3.3 context";
  const Case& terrell = kCases[0];
  EXPECT_FALSE(render(terrell, "--renderer raster --tessellation cpu", "cpu") ==
               render(terrell, "--renderer raster --tessellation gpu", "gpu"));
}

// ---------------------------------------------------------------------------------------------
// The rule.

TEST(TessellationRule, SoftwareRasterisersAreKnownByTheirRendererString) {
  for (const char* software :
       {"llvmpipe (LLVM 15.0.6, 256 bits)", "softpipe", "Software Rasterizer (swrast)",
        "Google SwiftShader", "ANGLE (Google, Vulkan 1.3.0 (SwiftShader Device (Subzero)))",
        "zink Vulkan 1.3(llvmpipe (LLVM 15.0.6, 256 bits) (MESA_LLVMPIPE))",
        "D3D12 (Microsoft Basic Render Driver)", "Apple Software Renderer"})
    EXPECT_TRUE(software_rasteriser(software)) << software;
  for (const char* hardware : {"NVIDIA GeForce RTX 4090/PCIe/SSE2", "NVIDIA H200/PCIe/SSE2",
                               "AMD Radeon RX 7900 XTX (radeonsi, navi31, LLVM 15.0.6, DRM 3.54)",
                               "Mesa Intel(R) UHD Graphics 620 (KBL GT2)", "Apple M2", "?", ""})
    EXPECT_FALSE(software_rasteriser(hardware)) << hardware;
}

TEST(TessellationRule, AutoCutsOnTheGpuOnlyOnAHardwareDriverWithTessellationShaders) {
  const GlDriver llvmpipe{true, "llvmpipe (LLVM 15.0.6, 256 bits)"};
  const GlDriver nvidia{true, "NVIDIA GeForce RTX 4090/PCIe/SSE2"};
  const GlDriver old_gpu{false, "Mesa Intel(R) HD Graphics 3000 (SNB GT2)"};
  const GlDriver old_software{false, "softpipe"};
  EXPECT_FALSE(tessellate_on_gpu(RasterTessellation::kAuto, llvmpipe));
  EXPECT_TRUE(tessellate_on_gpu(RasterTessellation::kAuto, nvidia));
  EXPECT_FALSE(tessellate_on_gpu(RasterTessellation::kAuto, old_gpu));
  EXPECT_FALSE(tessellate_on_gpu(RasterTessellation::kAuto, old_software));
  // As asked, whatever the driver; the GPU path needs OpenGL 4.
  for (const GlDriver& d : {llvmpipe, nvidia, old_gpu, old_software})
    EXPECT_FALSE(tessellate_on_gpu(RasterTessellation::kCpu, d)) << d.renderer;
  EXPECT_TRUE(tessellate_on_gpu(RasterTessellation::kGpu, llvmpipe));
  EXPECT_TRUE(tessellate_on_gpu(RasterTessellation::kGpu, nvidia));
  EXPECT_THROW(tessellate_on_gpu(RasterTessellation::kGpu, old_gpu), GlUnavailable);
  // The same facts, the same answer: nothing else enters.
  for (int i = 0; i < 100; ++i) ASSERT_TRUE(tessellate_on_gpu(RasterTessellation::kAuto, nvidia));
}

TEST(TessellationRule, TheRendererReportsThisMachinesDriver) {
  if (!have_gl()) GTEST_SKIP() << "no OpenGL 3.3 context";
  GlDriver driver;
  {
    const HeadlessGlContext context;
    const RasterRenderer renderer;
    driver = renderer.driver();
    EXPECT_FALSE(driver.renderer.empty());
    EXPECT_NE(context.description().find(driver.renderer), std::string::npos);
  }
  // The path `render` reports is the rule's.
  RasterStats stats;
  Scene scene = test::load_repository_scene("terrell.json");
  scene.camera.width = 64;
  scene.camera.height = 36;
  scene.camera.samples = 1;
  render_raster(scene, &stats);
  EXPECT_EQ(stats.gpu_tessellation, tessellate_on_gpu(RasterTessellation::kAuto, driver));
}

}  // namespace
}  // namespace lightcone
