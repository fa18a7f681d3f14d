// What an observer moving radially on a geodesic near a Schwarzschild black hole sees along one
// look direction, inside the horizon as well as outside (PHYSICS.md, "Curved spacetime"). G = c
// = 1, M the gravitational radius, f = 1 - 2M/r.
//
// The observer has energy per unit mass E = f dt/dtau and radial velocity u^r = dr/dtau (E^2 =
// f + (u^r)^2; falling u^r < 0). Its frame: e_0 = u and the radial unit vector e_r = (u^r / f,
// E) (in (t, r) components), orthogonal to it; outside the horizon this is the static frame
// boosted radially by v = u^r / E. A photon it receives along look direction l (unit; l_r along
// e_r, l_t = |l| across), with energy eps, has conserved energy E_ph = eps (E - u^r l_r) and
// angular momentum L = r eps l_t: no f appears, so the same holds at and inside r = 2M. Its
// backward ray has dr/dlambda proportional to E l_r - u^r.
#pragma once

#include <optional>

namespace lightcone {

struct RadialObserver {
  double mass = 1;
  double radius = 0;           // r > 0
  double energy = 1;           // E > 0
  double radial_velocity = 0;  // u^r = dr/dtau: +-sqrt(E^2 - f)
};

struct ObservedRay {
  double impact = 0;     // b = L / E_ph
  bool outward = false;  // the backward ray's r grows at the observer
  // The energy the observer measures per unit of the photon's conserved energy (what a static
  // observer far away measures): 1 / (E - u^r l_r).
  double energy = 1;
};

// The ray seen along the look direction with radial component cos_look and across-component
// sin_look >= 0 (cos^2 + sin^2 = 1); none for light of conserved energy <= 0, which only an
// observer inside the horizon can look along: it cannot have come from outside the hole (in a
// hole that formed by collapse, nothing sends it).
std::optional<ObservedRay> observed_ray(const RadialObserver& observer, double cos_look,
                                        double sin_look);

// The shadow's angular radius about the inward direction: the look angle beta from it where
// b = b_c = 3 sqrt(3) M, from r sin(beta) = b_c (E + u^r cos(beta)). Rays nearer the inward
// direction are captured (or, inside the horizon, have no positive energy or turn back short of
// the photon sphere).
double shadow_angle(const RadialObserver& observer);

// The range [lo, hi] of the energy the observer measures per unit conserved energy (ObservedRay's
// energy) over the rays that can bring it light from outside the photon sphere: every ray from
// r >= 3M, and below it, falling, the outward ones with b <= b_c (the others are captured).
struct EnergyRange {
  double lo = 1, hi = 1;
};
EnergyRange seen_energy_range(const RadialObserver& observer);

}  // namespace lightcone
