#include "lightcone/physics/radial_observer.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "lightcone/physics/schwarzschild.hpp"

namespace lightcone {

std::optional<ObservedRay> observed_ray(const RadialObserver& o, double cos_look, double sin_look) {
  const double per_energy = o.energy - o.radial_velocity * cos_look;  // E_ph / eps
  if (!(per_energy > 0)) return std::nullopt;
  ObservedRay ray;
  ray.impact = o.radius * sin_look / per_energy;
  ray.outward = o.energy * cos_look - o.radial_velocity > 0;
  ray.energy = 1 / per_energy;
  return ray;
}

double shadow_angle(const RadialObserver& o) {
  // r sin(beta) - b_c u^r cos(beta) = R sin(beta - phi) = b_c E, R = hypot(r, b_c u^r): the
  // first root from the outside of the photon sphere, the second (past 90 degrees when static)
  // inside it.
  const double bc = critical_impact_parameter(o.mass);
  const double big_r = std::hypot(o.radius, bc * o.radial_velocity);
  const double phi = std::atan2(bc * o.radial_velocity, o.radius);
  const double edge = std::asin(std::min(1.0, bc * o.energy / big_r));
  return o.radius >= 3 * o.mass ? phi + edge : phi + std::numbers::pi - edge;
}

EnergyRange seen_energy_range(const RadialObserver& o) {
  const double e = o.energy, u = o.radial_velocity;
  // E - u^r l_r over l_r in [-1, 1]: largest at l_r = -sign(u^r), least at l_r = sign(u^r).
  EnergyRange range{1 / (e + std::abs(u)), 1 / (e - std::abs(u))};
  // Rising (only outside), or from outside the photon sphere: every direction can bring light.
  if (u >= 0 || (o.radius >= 3 * o.mass && e > -u)) return range;
  // Falling below 3M light comes only along outward rays of b <= b_c: r l_t <= b_c (E - u^r l_r),
  // E - u^r l_r growing with l_r. The least is where equality holds, the larger root of
  // (u^2 + k^2) x^2 - 2 E u x + E^2 - k^2 = 0, k = r / b_c, x = l_r.
  const double k = o.radius / critical_impact_parameter(o.mass);
  const double root = std::sqrt(std::max(0.0, u * u + k * k - e * e));
  const double x = (e * u + k * root) / (u * u + k * k);
  range.hi = 1 / (e - u * x);
  return range;
}

}  // namespace lightcone
