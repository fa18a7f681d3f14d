// Equatorial coordinates on the sky (PHYSICS.md, "Stars"): in the sky's rest frame, before
// sky.rotation, the north celestial pole is +y and right ascension 0h on the equator is -z,
// right ascension growing toward -x.
#pragma once

#include "lightcone/physics/vec.hpp"

namespace lightcone {

// The unit direction of right ascension alpha and declination delta (radians):
// (-cos(delta) sin(alpha), sin(delta), -cos(delta) cos(alpha)).
Vec3 equatorial_direction(double right_ascension, double declination);

}  // namespace lightcone
