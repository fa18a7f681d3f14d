#include "lightcone/physics/accretion_disk.hpp"

#include <boost/math/special_functions/log1p.hpp>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

namespace lightcone {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kSqrt3 = std::numbers::sqrt3;
constexpr double kSqrt6 = 2.449489742783178098197284074705891391965947480656670128432692567;

// ln(1 + q) - q to full precision. For 0 <= q <= 0.95, where Boost's log1pmx sums the Taylor
// series of ln(1 + q) (hundreds of terms as q -> 0.95): with s = q / (2 + q) <= 0.33,
// ln(1 + q) = 2 atanh(s) and q = 2s / (1 - s), so
//   ln(1 + q) - q = -2 s^2 / (1 - s) + 2 s^3 (1/3 + s^2/5 + s^4/7 + ...),
// the second term under a tenth of the first, and s^2 <= 0.11: 16 terms at most. Within 4 eps
// of a quad-precision reference on (0, 0.95] (Boost's series: 22 eps). Elsewhere Boost's
// ln(1 + q) - q, which cancels little there.
double log1pmx(double q) {
  if (!(q >= 0 && q <= 0.95)) {
    using DoublePolicy =
        boost::math::policies::policy<boost::math::policies::promote_double<false>>;
    return boost::math::log1pmx(q, DoublePolicy());
  }
  const double s = q / (2 + q), s2 = s * s;
  double sum = 0, power = 1;
  for (int k = 3;; k += 2) {
    const double term = power / k;
    sum += term;
    if (term <= std::numeric_limits<double>::epsilon() / 2 * sum) break;
    power *= s2;
  }
  return -2 * s2 / (1 - s) + 2 * s * s2 * sum;
}

// The Page-Thorne flux (Page & Thorne 1974; Novikov & Thorne 1973), for zero torque at the ISCO:
//   F(r) = -(Mdot / (4 pi sqrt(-g))) Omega_{,r} / (E - Omega L)^2
//          * int_{r_isco}^r (E - Omega L) L_{,r} dr
// with the circular orbits' specific energy and angular momentum E = f / sqrt(1 - 3M/r),
// L = sqrt(M r) / sqrt(1 - 3M/r), Omega = sqrt(M / r^3), and sqrt(-g) = r in the equatorial
// plane. Here E - Omega L = sqrt(1 - 3M/r), L_{,r} = sqrt(M) (r - 6M) / (2 (r - 3M)^(3/2)), so with
// x = r/M, y = sqrt(x) the integrand is M (y^2 - 6) / (y^2 - 3) dy = M (1 - 3 / (y^2 - 3)) dy and
//   int = M I(y),  I(y) = y - sqrt 6 - (sqrt 3 / 2) ln(1 + q),
//   1 + q = (y - sqrt 3)(sqrt 6 + sqrt 3) / ((y + sqrt 3)(sqrt 6 - sqrt 3)),
//   q = 2 sqrt 3 (y - sqrt 6) / ((y + sqrt 3)(sqrt 6 - sqrt 3)),
// and with Omega_{,r} = -(3/2) sqrt(M) r^(-5/2) the flux is
//   F = 3 Mdot / (8 pi M^2) I / ((x - 3) x^(5/2)).
// Near the ISCO I vanishes like (x - 6)^2 while its terms vanish like x - 6; since
// y - sqrt 6 - (sqrt 3 / 2) q = (y - sqrt 6)^2 / (y + sqrt 3) exactly,
//   I = (y - sqrt 6)^2 / (y + sqrt 3) - (sqrt 3 / 2) (ln(1 + q) - q),
// both terms positive (log1pmx above is ln(1 + q) - q to full precision), nothing cancels.
double flux_integral(double x) {
  const double y = std::sqrt(x);
  const double d = (x - 6) / (y + kSqrt6);  // y - sqrt 6
  const double q = 2 * kSqrt3 * d / ((y + kSqrt3) * (kSqrt6 - kSqrt3));
  return d * d / (y + kSqrt3) - kSqrt3 / 2 * log1pmx(q);
}

// M^2 F / Mdot as a function of x = r/M (x > 6).
double flux_shape(double x) {
  return 3 / (8 * std::numbers::pi) * flux_integral(x) / ((x - 3) * x * x * std::sqrt(x));
}

// The radius of the peak in units of M: dF/dx = 0, with dI/dx = (x - 6) / (2 sqrt x (x - 3))
// and d ln((x - 3) x^(5/2)) / dx = (7x - 15) / (2 x (x - 3)), is (x - 6) sqrt x = (7x - 15) I.
// That function of x changes sign once on [7, 20] (positive, then negative); TOMS 748 (Boost) on
// the bracket, to the last bit, once per process. (Maximising F itself, e.g. with Brent, would
// find the radius only to sqrt(eps), the peak being flat.)
FluxPeak peak_shape() {
  const auto h = [](double x) { return (x - 6) * std::sqrt(x) - (7 * x - 15) * flux_integral(x); };
  std::uintmax_t iterations = 200;
  const auto [lo, hi] = boost::math::tools::toms748_solve(
      h, 7.0, 20.0, boost::math::tools::eps_tolerance<double>(), iterations);
  const double x = (lo + hi) / 2;
  return {x, flux_shape(x)};
}
// Computed once (in units of M: radius / M and M^2 F_peak).
const FluxPeak& unit_peak() {
  static const FluxPeak peak = peak_shape();
  return peak;
}

}  // namespace

double isco_radius(double mass) {
  return 6 * mass;
}

double photon_sphere_radius(double mass) {
  return 3 * mass;
}

double circular_orbit_angular_velocity(double mass, double r) {
  if (!(r > 3 * mass)) return kNaN;
  return std::sqrt(mass / r) / r;
}

double circular_orbit_time_dilation(double mass, double r) {
  if (!(r > 3 * mass)) return kNaN;
  return 1 / std::sqrt(1 - 3 * mass / r);
}

double circular_orbit_local_speed(double mass, double r) {
  if (!(r > 3 * mass)) return kNaN;
  return std::sqrt(mass / (r - 2 * mass));
}

double circular_orbit_frequency_shift(double mass, double r, double lambda) {
  if (!(r > 3 * mass)) return kNaN;
  return std::sqrt(1 - 3 * mass / r) / (1 - circular_orbit_angular_velocity(mass, r) * lambda);
}

double novikov_thorne_flux(double mass, double r) {
  const double x = r / mass;
  if (!(x > 6)) return std::isnan(x) ? kNaN : 0.0;
  if (std::isinf(x)) return 0;
  return flux_shape(x) / (mass * mass);
}

FluxPeak novikov_thorne_peak(double mass) {
  const FluxPeak& unit = unit_peak();
  return {unit.radius * mass, unit.flux / (mass * mass)};
}

double disk_temperature_ratio(double mass, double r) {
  const double x = r / mass;
  if (!(x > 6)) return std::isnan(x) ? kNaN : 0.0;
  if (std::isinf(x)) return 0;
  return std::sqrt(std::sqrt(flux_shape(x) / unit_peak().flux));  // the fourth root
}

}  // namespace lightcone
