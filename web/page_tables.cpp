// The RGB-to-spectrum coefficient table in the page. The native library embeds the whole
// table (9 MB, fitted at build time by tools/rgb2spec_gen); the page fits only the columns its
// scenes' colours use, the first time each is asked for, with the same fit (its columns are
// independent of each other: tools/rgb2spec_fit.hpp). A colour costs at most four columns of
// 64 fits, a few milliseconds.
#include <cstddef>
#include <vector>

#include "lightcone/color/rgb_spectrum.hpp"
#include "lightcone/color/sigmoid_polynomial.hpp"
#include "rgb2spec_fit.hpp"

const float* lightcone::detail::rgb_to_spectrum_table(int l, int j, int i) {
  constexpr int res = kRgbToSpectrumRes;
  static std::vector<float> table(kRgbToSpectrumTableFloats);
  static std::vector<bool> fitted(static_cast<std::size_t>(3) * res * res);
  static const rgb2spec::Fitter fitter;
  for (int b = 0; b < 2; ++b)
    for (int a = 0; a < 2; ++a) {
      const std::size_t column = (static_cast<std::size_t>(l) * res + j + b) * res + i + a;
      if (fitted[column]) continue;
      fitter.fit_column(res, l, j + b, i + a, table.data());
      fitted[column] = true;
    }
  return table.data();
}
