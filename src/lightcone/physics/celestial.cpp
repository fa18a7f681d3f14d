#include "lightcone/physics/celestial.hpp"

#include <cmath>

namespace lightcone {

Vec3 equatorial_direction(double right_ascension, double declination) {
  const double c = std::cos(declination);
  return {-c * std::sin(right_ascension), std::sin(declination), -c * std::cos(right_ascension)};
}

}  // namespace lightcone
