#include "lightcone/color/sigmoid_polynomial.hpp"

#include <cmath>
#include <vector>

#include "lightcone/color/spectrum.hpp"

namespace lightcone {
namespace {

// BlackbodySpectrum::with_luminance normalises with xyz_from_spectrum(), the 1 nm quadrature
// that the fit and the tests use, so the reference illuminant's Y is 1 to rounding.
const BlackbodySpectrum& exact_illuminant() {
  static const BlackbodySpectrum illuminant =
      BlackbodySpectrum::with_luminance(kReferenceIlluminantTemperature, 1.0);
  return illuminant;
}

// The spectral renderer evaluates the illuminant eight times per camera sample, and Planck's
// exponential dominated its cost, so it is tabulated against log2(lambda) and interpolated
// linearly. The relative error is about (x ln2 / kNodesPerOctave)^2 / 8 with x = hc/(lambda k T):
// below 1e-5 in the visible, 1e-4 at 50 nm. Outside the table Planck's law is evaluated.
constexpr double kTableLog2Min = 4.0;   // 16 nm
constexpr double kTableLog2Max = 20.0;  // about 1 mm
constexpr int kNodesPerOctave = 1024;

const std::vector<double>& illuminant_table() {
  static const std::vector<double> table = [] {
    const int nodes = static_cast<int>((kTableLog2Max - kTableLog2Min) * kNodesPerOctave) + 1;
    std::vector<double> t(nodes);
    for (int i = 0; i < nodes; ++i)
      t[i] =
          exact_illuminant()(std::exp2(kTableLog2Min + static_cast<double>(i) / kNodesPerOctave));
    return t;
  }();
  return table;
}

}  // namespace

double reference_illuminant(double lambda_nm) {
  const std::vector<double>& table = illuminant_table();
  const double position = (std::log2(lambda_nm) - kTableLog2Min) * kNodesPerOctave;
  if (!(position >= 0) || !(position < static_cast<double>(table.size() - 1)))
    return exact_illuminant()(lambda_nm);
  const auto i = static_cast<std::size_t>(position);
  const double f = position - static_cast<double>(i);
  return table[i] + f * (table[i + 1] - table[i]);
}

LinearRgb reference_white() {
  static const LinearRgb white =
      linear_srgb_from_xyz(xyz_from_spectrum([](double l) { return reference_illuminant(l); }));
  return white;
}

}  // namespace lightcone
