#include "lightcone/physics/retarded_time.hpp"

#include <cmath>

namespace lightcone {

double retarded_delay(const Vec3& delta, const Vec3& beta) {
  // (1 - b^2) tau^2 + 2 (b.delta) tau - |delta|^2 = 0; take the non-negative root.
  const double bd = dot(beta, delta);
  const double d2 = dot(delta, delta);
  const double one_minus_b2 = 1.0 - dot(beta, beta);
  const double root = std::sqrt(bd * bd + one_minus_b2 * d2);
  if (bd > 0) return d2 / (bd + root);  // avoids cancellation in -bd + root
  return (root - bd) / one_minus_b2;
}

}  // namespace lightcone
