// A packet of camera rays near the hole has its paths prepared together (photon_orbits,
// prepare_sweeps, curved_paths, follow_curved_rays: their Landen moduli and Carlson integrals run
// side by side): each must be the ray's own to the bit, as photon_orbit, prepare_sweep, curved_path
// and follow_curved_ray give it alone, for every kind of path: radial (b = 0) and nearly so, at
// and beside the critical impact parameter, turning and captured, from inside the photon sphere
// and the horizon, outward and inward, in packets of every size. G = c = 1, M = 1.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

#include "lightcone/frame/curved_ray.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/physics/radial_observer.hpp"
#include "lightcone/physics/schwarzschild.hpp"

namespace lightcone {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Equal to the bit (a NaN equal to the same NaN).
testing::AssertionResult same_bits(double a, double b) {
  if (std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b))
    return testing::AssertionSuccess();
  return testing::AssertionFailure() << a << " against " << b << " alone";
}

void expect_same_sweep(const AngleSweep& a, const AngleSweep& b) {
  EXPECT_EQ(a.form, b.form);
  for (const auto field : {&AngleSweep::r0, &AngleSweep::angle_total, &AngleSweep::turning_radius,
                           &AngleSweep::angle_to_turn, &AngleSweep::end, &AngleSweep::horizon,
                           &AngleSweep::phase, &AngleSweep::rate, &AngleSweep::scale,
                           &AngleSweep::coef, &AngleSweep::impact, &AngleSweep::w_neg})
    EXPECT_TRUE(same_bits(a.*field, b.*field));
  EXPECT_EQ(a.jacobi.steps, b.jacobi.steps);
  EXPECT_TRUE(same_bits(a.jacobi.rate, b.jacobi.rate));
}

struct Start {
  double impact, r0;
  bool outward;
};

// Impact parameters of every kind, and the radii a ray may start from.
std::vector<Start> starts() {
  const double bc = critical_impact_parameter(1);
  const std::vector<double> impacts = {0,
                                       1e-300,
                                       1e-12,
                                       1e-6,
                                       0.5,
                                       3,
                                       bc * (1 - 1e-9),
                                       std::nextafter(bc, 0.0),
                                       bc,
                                       std::nextafter(bc, kInf),
                                       bc * (1 + 1e-9),
                                       5.3,
                                       6,
                                       10,
                                       25,
                                       1e3,
                                       1e8};
  const std::vector<double> radii = {1.5, 2, 2.5, 3, 4, 8, 60, 1e6, kInf};
  std::vector<Start> s;
  for (const double b : impacts) {
    std::vector<double> from = radii;
    const PhotonOrbit o = photon_orbit(1, b);
    if (o.turning) from.insert(from.end(), {o.periapsis, o.inner_turning});
    for (const double r0 : from)
      for (const bool outward : {false, true}) s.push_back({b, r0, outward});
  }
  return s;
}

TEST(CurvedPaths, OrbitsTakenTogetherAreEachOwn) {
  std::vector<double> impacts;
  for (const Start& s : starts())
    if (impacts.empty() || impacts.back() != s.impact) impacts.push_back(s.impact);
  std::size_t first = 0;
  for (int size = 1; first < impacts.size(); size = size % kMaxSweeps + 1) {
    const int n = static_cast<int>(std::min<std::size_t>(size, impacts.size() - first));
    PhotonOrbit orbits[kMaxSweeps];
    PhotonOrbit* out[kMaxSweeps];
    for (int i = 0; i < n; ++i) out[i] = &orbits[i];
    photon_orbits(1, &impacts[first], out, n);
    for (int i = 0; i < n; ++i) {
      SCOPED_TRACE(testing::Message() << "b " << impacts[first + i] << " in a packet of " << n);
      const PhotonOrbit alone = photon_orbit(1, impacts[first + i]);
      const PhotonOrbit& o = orbits[i];
      EXPECT_EQ(o.turning, alone.turning);
      EXPECT_EQ(o.critical, alone.critical);
      for (const auto field :
           {&PhotonOrbit::periapsis, &PhotonOrbit::inner_turning, &PhotonOrbit::w_neg,
            &PhotonOrbit::v_pos, &PhotonOrbit::v_gap, &PhotonOrbit::scale, &PhotonOrbit::quad_a,
            &PhotonOrbit::modulus_c2, &PhotonOrbit::pair_c, &PhotonOrbit::pair_n})
        EXPECT_TRUE(same_bits(o.*field, alone.*field));
      ASSERT_EQ(o.jacobi.steps, alone.jacobi.steps);
      EXPECT_EQ(o.jacobi.unit, alone.jacobi.unit);
      for (int k = 0; k < o.jacobi.steps; ++k) {
        EXPECT_TRUE(same_bits(o.jacobi.k[k], alone.jacobi.k[k]));
        EXPECT_TRUE(same_bits(o.jacobi.c[k], alone.jacobi.c[k]));
      }
      EXPECT_TRUE(same_bits(o.jacobi.rate, alone.jacobi.rate));
      EXPECT_TRUE(same_bits(o.jacobi.k2, alone.jacobi.k2));
      EXPECT_TRUE(same_bits(o.jacobi.kc2, alone.jacobi.kc2));
    }
    first += n;
  }
}

TEST(CurvedPaths, SweepsPreparedTogetherAreEachRaysOwn) {
  const std::vector<Start> all = starts();
  std::vector<PhotonOrbit> orbits;
  for (const Start& s : all) orbits.push_back(photon_orbit(1, s.impact));
  // Packets of each size from 1 to kMaxSweeps, in turn, over the whole list.
  std::size_t first = 0;
  for (int size = 1; first < all.size(); size = size % kMaxSweeps + 1) {
    const int n = static_cast<int>(std::min<std::size_t>(size, all.size() - first));
    SweepStart packet[kMaxSweeps];
    AngleSweep sweeps[kMaxSweeps];
    AngleSweep* out[kMaxSweeps];
    for (int i = 0; i < n; ++i) {
      const Start& s = all[first + i];
      packet[i] = {&orbits[first + i], s.r0, s.outward};
      out[i] = &sweeps[i];
    }
    prepare_sweeps(packet, out, n);
    for (int i = 0; i < n; ++i) {
      const Start& s = all[first + i];
      SCOPED_TRACE(testing::Message() << "b " << s.impact << " r0 " << s.r0 << " outward "
                                      << s.outward << " in a packet of " << n);
      expect_same_sweep(sweeps[i], prepare_sweep(orbits[first + i], s.r0, s.outward));
    }
    first += n;
  }
}

// A static camera at r, boosted toward the hole at a third of c (so that its rays are aberrated),
// or one falling from rest at 30 M (inside the horizon too), with a tilted disk.
HoleView camera_at(double r, bool falling) {
  HoleView v;
  v.camera_radius = r;
  v.outward = {0, 0, 1};
  v.world_to_sky = boost({});
  v.disk = AccretionDisk{};
  v.disk->normal = normalize(Vec3{0, 1, 0.3});
  if (falling) {
    const double e = std::sqrt(1 - 2 / 30.0);
    v.falling = RadialObserver{1, r, e, -std::sqrt(e * e - (1 - 2 / r))};
    return v;
  }
  v.camera_lapse = std::sqrt(1 - 2 / r);
  const Vec3 beta{0, 0, -1.0 / 3};
  v.camera_rapidity = rapidity(beta);
  v.trace_to_static = lorentz_inverse(boost(beta));
  return v;
}

// Looks over the whole sphere, straight at and away from the hole, and either side of the
// shadow's edge of the static camera at r (the critical curve, where the paths wind).
std::vector<Vec3> looks(double r) {
  std::vector<Vec3> u = {{0, 0, -1}, {0, 0, 1}};
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j < 12; ++j) {
      const double theta = std::numbers::pi * i / 40, around = 2 * std::numbers::pi * j / 12;
      u.push_back({std::sin(theta) * std::cos(around), std::sin(theta) * std::sin(around),
                   -std::cos(theta)});
    }
  const double edge = static_shadow_angle(1, r);
  for (const double off : {-1e-9, -1e-14, 0.0, 1e-14, 1e-9})
    u.push_back({std::sin(edge + off), 0, -std::cos(edge + off)});
  return u;
}

TEST(CurvedPaths, PacketOfCameraRaysIsEachRaysOwn) {
  for (const auto& [r, falling] : {std::pair{60.0, false},
                                   {6.0, false},
                                   {2.5, false},
                                   {2.5, true},
                                   {2.0, true},
                                   {1.2, true}}) {
    const HoleView hole = camera_at(r, falling);
    const std::vector<Vec3> u = looks(r);
    std::vector<CurvedPath> paths(u.size());
    std::vector<CurvedRay> rays(u.size());
    curved_paths(hole, u, paths);
    follow_curved_rays(hole, u, nullptr, rays);
    for (std::size_t i = 0; i < u.size(); ++i) {
      SCOPED_TRACE(testing::Message()
                   << "r " << r << (falling ? " falling" : " static") << ", look " << i);
      const CurvedPath alone = curved_path(hole, u[i]);
      EXPECT_EQ(paths[i].dark, alone.dark);
      EXPECT_TRUE(same_bits(paths[i].impact, alone.impact));
      expect_same_sweep(paths[i].sweep, alone.sweep);
      const CurvedRay ray = follow_curved_ray(hole, u[i]);
      EXPECT_EQ(rays[i].end, ray.end);
      EXPECT_EQ(rays[i].order, ray.order);
      EXPECT_TRUE(same_bits(rays[i].phi, ray.phi));
      EXPECT_TRUE(same_bits(rays[i].shift, ray.shift));
      EXPECT_TRUE(same_bits(rays[i].disk_radius, ray.disk_radius));
      for (int k = 0; k < 3; ++k)
        EXPECT_TRUE(same_bits(rays[i].sky_direction[k], ray.sky_direction[k]));
    }
  }
}

}  // namespace
}  // namespace lightcone
