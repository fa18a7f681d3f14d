#include "support/test_support.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "lightcone/io/input_error.hpp"
#include "lightcone/io/scene_file.hpp"

namespace lightcone::test {

namespace fs = std::filesystem;

Object make_object(const std::string& name, Shape shape, Vec3 position, Vec3 velocity,
                   Material material) {
  Object o;
  o.name = name;
  o.shape = std::move(shape);
  o.world_line.position = position;
  o.world_line.velocity = velocity;
  o.material = std::move(material);
  return o;
}

Material solid(Rgb colour) {
  Material m;
  m.pattern = SolidColor{colour};
  return m;
}

Material lit(Rgb albedo) {
  Material m;
  m.pattern = SolidColor{albedo};
  m.unlit = false;
  return m;
}

double minkowski(const Vec4& a, const Vec4& b) {
  return -a.t * b.t + dot(a.x, b.x);
}

double bisect_decreasing(const std::function<double(double)>& f, double lo, double hi) {
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) > 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double fraction_differing(const Image& a, const Image& b) {
  std::size_t bad = 0;
  for (std::size_t p = 0; p < a.rgb.size(); p += 3) {
    bool differ = false;
    for (int c = 0; c < 3; ++c) {
      const double x = a.rgb[p + c], y = b.rgb[p + c];
      differ |= std::abs(x - y) > 1e-4 * std::max({1.0, std::abs(x), std::abs(y)});
    }
    bad += differ;
  }
  return static_cast<double>(bad) / static_cast<double>(a.rgb.size() / 3);
}

void expect_vec(const Vec3& v, const Vec3& expected, double tolerance) {
  EXPECT_NEAR(v.x, expected.x, tolerance) << "x";
  EXPECT_NEAR(v.y, expected.y, tolerance) << "y";
  EXPECT_NEAR(v.z, expected.z, tolerance) << "z";
}

void TempDirTest::SetUp() {
  dir_ = fresh_temp_dir(testing::UnitTest::GetInstance()->current_test_info()->name());
}

void TempDirTest::TearDown() {
  fs::remove_all(dir_);
}

fs::path TempDirTest::write(const std::string& name, const std::string& content) const {
  const fs::path path = dir_ / name;
  fs::create_directories(path.parent_path());
  write_text(path, content);
  return path;
}

IntegratedOrbit integrate_orbit(double m, double b, double u0, double du0, double phi, int steps) {
  struct State {
    long double u, du, t;
  };
  const auto deriv = [&](const State& s) {
    const long double r = 1 / s.u;
    return State{s.du, 3 * m * s.u * s.u - s.u, r * r / (b * (1 - 2 * m * s.u))};
  };
  const auto along = [](const State& s, const State& k, long double h) {
    return State{s.u + h * k.u, s.du + h * k.du, 0};
  };
  State s{u0, du0, 0};
  const long double h = static_cast<long double>(phi) / steps;
  for (int i = 0; i < steps; ++i) {
    const State k1 = deriv(s), k2 = deriv(along(s, k1, h / 2)), k3 = deriv(along(s, k2, h / 2)),
                k4 = deriv(along(s, k3, h));
    s = {s.u + h / 6 * (k1.u + 2 * k2.u + 2 * k3.u + k4.u),
         s.du + h / 6 * (k1.du + 2 * k2.du + 2 * k3.du + k4.du),
         s.t + h / 6 * (k1.t + 2 * k2.t + 2 * k3.t + k4.t)};
  }
  return {static_cast<double>(1 / s.u), static_cast<double>(s.t)};
}

IntegratedOrbit integrate_orbit_from(double m, double r0, double cos_alpha, double sin_alpha,
                                     double phi, int steps) {
  const double f0 = 1 - 2 * m / r0;
  return integrate_orbit(m, r0 * sin_alpha / std::sqrt(f0), 1 / r0,
                         -std::sqrt(f0) * cos_alpha / sin_alpha / r0, phi, steps);
}

fs::path fresh_temp_dir(const std::string& name) {
  static std::atomic<int> counter{0};
  const fs::path dir = fs::temp_directory_path() / ("lightcone-test-" + std::to_string(getpid()) +
                                                    "-" + std::to_string(counter++) + "-" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void write_text(const fs::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
}

Scene scene_from_json(const std::string& json) {
  const fs::path file = fresh_temp_dir("scene") / "scene.json";
  write_text(file, json);
  SceneLoadReport report;
  return load_scene_file(file, {}, report);
}

Scene load_repository_scene(const std::string& name) {
  SceneLoadReport report;
  return load_scene_file(fs::path(LIGHTCONE_SOURCE_DIR) / "scenes" / name, {}, report);
}

static std::string read_all(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

CommandResult run_command(const std::string& command_line) {
  const fs::path dir = fresh_temp_dir("cmd");
  const std::string command = command_line + " >'" + (dir / "out").string() + "' 2>'" +
                              (dir / "err").string() + "' </dev/null";
  const int raw = std::system(command.c_str());
  CommandResult r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = read_all(dir / "out");
  r.err = read_all(dir / "err");
  fs::remove_all(dir);
  return r;
}

CommandResult run_lightcone(const std::string& arguments, const std::string& environment) {
  return run_command(environment + " '" + LIGHTCONE_BINARY + "' " + arguments);
}

CommandResult run_lightcone_on_terminal(const std::string& arguments, int columns) {
  const int master = posix_openpt(O_RDWR | O_NOCTTY);
  if (master < 0 || grantpt(master) != 0 || unlockpt(master) != 0)
    throw std::runtime_error("cannot open a pseudo-terminal");
  if (columns > 0) {
    winsize size{};
    size.ws_row = 24;
    size.ws_col = static_cast<unsigned short>(columns);
    if (ioctl(master, TIOCSWINSZ, &size) != 0)
      throw std::runtime_error("cannot set the pseudo-terminal's width");
  }
  const std::string terminal = ptsname(master);
  // Kept open here so that the terminal is never hung up while the reader waits on it.
  const int slave = open(terminal.c_str(), O_RDWR | O_NOCTTY);
  if (slave < 0) throw std::runtime_error("cannot open " + terminal);
  std::string received;
  std::atomic<bool> finished{false};
  // Drains the terminal while the command runs, so a chatty program never blocks on it.
  std::thread reader([&] {
    char buffer[4096];
    for (;;) {
      pollfd p{master, POLLIN, 0};
      if (poll(&p, 1, 50) > 0 && (p.revents & POLLIN)) {
        const ssize_t n = read(master, buffer, sizeof buffer);
        if (n <= 0) break;
        received.append(buffer, static_cast<std::size_t>(n));
      } else if (finished) {
        break;
      }
    }
  });
  const fs::path dir = fresh_temp_dir("tty");
  const std::string command = std::string("'") + LIGHTCONE_BINARY + "' " + arguments + " >'" +
                              (dir / "out").string() + "' 2>'" + terminal + "' </dev/null";
  const int raw = std::system(command.c_str());
  finished = true;
  reader.join();
  close(slave);
  close(master);
  CommandResult r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = read_all(dir / "out");
  r.err = received;
  fs::remove_all(dir);
  return r;
}

std::string quoted(const std::filesystem::path& p) {
  return fmt::format("'{}'", p.string());
}

std::string bytes_of(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

bool have_program(const char* program) {
  return std::system((std::string("command -v ") + program + " >/dev/null 2>&1").c_str()) == 0;
}

std::string base64(const std::string& data) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < data.size(); i += 3) {
    std::uint32_t n = std::uint8_t(data[i]) << 16;
    if (i + 1 < data.size()) n |= std::uint8_t(data[i + 1]) << 8;
    if (i + 2 < data.size()) n |= std::uint8_t(data[i + 2]);
    out += table[(n >> 18) & 63];
    out += table[(n >> 12) & 63];
    out += i + 1 < data.size() ? table[(n >> 6) & 63] : '=';
    out += i + 2 < data.size() ? table[n & 63] : '=';
  }
  return out;
}

const NamedChannel& channel(const Image& image, const std::string& name) {
  for (const NamedChannel& c : image.channels)
    if (c.name == name) return c;
  ADD_FAILURE() << "no channel " << name;
  static const NamedChannel none;
  return none;
}

}  // namespace lightcone::test
