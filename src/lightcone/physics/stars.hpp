// Stars as point sources (PHYSICS.md, "Stars"; docs/design/stars.md): a star's colour and
// brightness from its catalogue entry.
#pragma once

namespace lightcone {

// The temperature (kelvin) of the blackbody whose colour index is B-V: Ballesteros, "New
// insights into black bodies" (2012), T = 4600 K (1 / (0.92 (B-V) + 1.7) + 1 / (0.92 (B-V) +
// 0.62)). Defined for B-V > -0.4 (hotter than any star). A star is not quite a blackbody:
// against measured effective temperatures the Sun's comes out within 0.1 %, Procyon's 4 % high.
double star_temperature(double b_minus_v);

// The flux of magnitude m over that of magnitude 0: 10^(-0.4 m) (Pogson 1856: five magnitudes
// are a factor of 100).
double magnitude_flux_ratio(double magnitude);

}  // namespace lightcone
