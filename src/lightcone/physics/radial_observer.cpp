#include "lightcone/physics/radial_observer.hpp"

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

}  // namespace lightcone
