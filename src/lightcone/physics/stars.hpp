// Stars as point sources (PHYSICS.md, "Stars"; docs/design/stars.md): a star's colour and
// brightness from its catalogue entry.
#pragma once

namespace lightcone {

// The temperature (kelvin) of the blackbody whose colour index is B-V: Ballesteros, "New
// insights into black bodies" (2012), T = 4600 K (1 / (0.92 (B-V) + 1.7) + 1 / (0.92 (B-V) +
// 0.62)), for B-V from kBluestColourIndex to kReddestColourIndex. A star is not quite a
// blackbody: against measured effective temperatures the Sun's comes out within 0.1 %,
// Procyon's 4 % high.
double star_temperature(double b_minus_v);

// The B-V a star may have (a catalogue is refused outside it). Below -0.674 Ballesteros' T is
// infinite or negative; no star is bluer than about -0.33 (the hottest O stars), and the bluest
// of the 125,982 stars of KStars' stars.dat is -0.40 (21,700 K here). Carbon stars are the
// reddest: W Ori, the reddest of the bundled catalogue, has 3.33, and T Lyr, the reddest of
// stars.dat, 5.46; at 6 the formula gives 1,390 K, cooler than any star.
inline constexpr double kBluestColourIndex = -0.4;
inline constexpr double kReddestColourIndex = 6.0;

// The flux of magnitude m over that of magnitude 0: 10^(-0.4 m) (Pogson 1856: five magnitudes
// are a factor of 100).
double magnitude_flux_ratio(double magnitude);

// The V a star may have (a catalogue is refused outside it): from brighter than Sirius (-1.46,
// the brightest star of the night sky; Hoffleit & Warren 1991) to about the depth of the deepest
// images (the Hubble Ultra Deep Field reaches about 29; Beckwith et al. 2006), far fainter than
// any star a catalogue gives a colour for.
inline constexpr double kBrightestMagnitude = -2.0;
inline constexpr double kFaintestMagnitude = 30.0;

}  // namespace lightcone
