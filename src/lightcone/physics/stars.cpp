#include "lightcone/physics/stars.hpp"

#include <cmath>

namespace lightcone {

double star_temperature(double b_minus_v) {
  const double x = 0.92 * b_minus_v;
  return 4600 * (1 / (x + 1.7) + 1 / (x + 0.62));
}

double magnitude_flux_ratio(double magnitude) {
  return std::pow(10.0, -0.4 * magnitude);
}

}  // namespace lightcone
