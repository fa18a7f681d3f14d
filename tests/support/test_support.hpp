// Helpers shared by the tests: temporary folders, scenes from JSON text, running the CLI.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "lightcone/scene/scene.hpp"

namespace lightcone::test {

// An object with a shape, a world-line through `position` at t = 0, and a material.
Object make_object(const std::string& name, Shape shape, Vec3 position, Vec3 velocity,
                   Material material);

// An unlit material of one colour.
Material solid(Rgb colour);

// A lit (Lambertian) material: the pattern is the albedo.
Material lit(Rgb albedo);

// The interval a.b with signature (- + + +).
double minkowski(const Vec4& a, const Vec4& b);

// The root of a decreasing function in [lo, hi] (f(lo) > 0 > f(hi)) by plain bisection, 200
// halvings: the independent check of the solvers the renderers use.
double bisect_decreasing(const std::function<double(double)>& f, double lo, double hi);

// Fraction of pixels whose colour differs by more than 1e-4 (relative above 1) in some channel:
// the comparison of the renders of one physical scene described in two frames.
double fraction_differing(const Image& a, const Image& b);

// Each component of `v` within `tolerance` of `expected`'s.
void expect_vec(const Vec3& v, const Vec3& expected, double tolerance = 1e-12);

// A fixture with a fresh folder per test, removed afterwards.
class TempDirTest : public testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;
  // Writes `content` to `name` in the folder (making its folders) and returns its path.
  std::filesystem::path write(const std::string& name, const std::string& content) const;

  std::filesystem::path dir_;
};

// Light about a hole of mass m (G = c = 1): the orbit equation u'' = 3 M u^2 - u, and the
// coordinate time dt/dphi = r^2 / (b f) along it, integrated step by step (classical RK4 in long
// double, `steps` equal steps over the angle `phi`) from u0 = 1/r0 and du0 = du/dphi: the radius
// and the time at the end. The independent check of the closed-form geodesics.
struct IntegratedOrbit {
  double r = 0, t = 0;
};
IntegratedOrbit integrate_orbit(double m, double b, double u0, double du0, double phi, int steps);
// The same for the ray leaving radius r0 at static-frame angle alpha from the outward radial:
// dr/dphi = r sqrt(f) cot(alpha) there, so du/dphi = -sqrt(f0) cot(alpha) / r0.
IntegratedOrbit integrate_orbit_from(double m, double r0, double cos_alpha, double sin_alpha,
                                     double phi, int steps);

// A fresh, empty folder under the system's temporary folder.
std::filesystem::path fresh_temp_dir(const std::string& name);

void write_text(const std::filesystem::path& file, const std::string& text);

// Writes `json` to a scene file in a fresh folder and loads it (warnings ignored).
Scene scene_from_json(const std::string& json);

// A scene file from the repository's scenes/ folder.
Scene load_repository_scene(const std::string& name);

// A path in single quotes, for a shell command line.
std::string quoted(const std::filesystem::path& p);

// A file's bytes ("" if it cannot be read).
std::string bytes_of(const std::filesystem::path& file);

// Whether `program` is on the PATH.
bool have_program(const char* program);

// Base64 (RFC 4648, padded): data URIs in test meshes.
std::string base64(const std::string& data);

struct CommandResult {
  int status = -1;
  std::string out, err;
};
// Runs a shell command line (quoted by the caller), its output and errors collected.
CommandResult run_command(const std::string& command_line);
// Runs the built `lightcone` binary with the given arguments (shell-quoted by the caller), with
// `environment` ("NAME=value ...", shell-quoted) added to its environment.
CommandResult run_lightcone(const std::string& arguments, const std::string& environment = "");
// The same with stderr on a pseudo-terminal (so the program sees a terminal there); `err` is what
// the terminal received (its line discipline turns "\n" into "\r\n"); `columns` > 0 sets the
// terminal's width (else the pseudo-terminal reports none).
CommandResult run_lightcone_on_terminal(const std::string& arguments, int columns = 0);

// The image's output-variable channel by name (a test failure, and an empty channel, if none).
const NamedChannel& channel(const Image& image, const std::string& name);

}  // namespace lightcone::test
