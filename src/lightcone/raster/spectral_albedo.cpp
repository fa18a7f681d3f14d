#include "lightcone/raster/spectral_albedo.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "lightcone/color/cie.hpp"
#include "lightcone/color/cie_data.hpp"
#include "lightcone/color/rgb_spectrum.hpp"

namespace lightcone {
namespace {

// Samples of a light's spectrum per unit of ln(lambda) (0.15 nm apart at 600 nm: linear
// interpolation between them is within some 1e-6 of the spectrum), in rows of kRowTexels.
constexpr double kSamplesPerLogUnit = 4096;
constexpr int kRowTexels = 1024;

GLuint nearest_texture(GLenum target) {
  GLuint texture = 0;
  glGenTextures(1, &texture);
  glBindTexture(target, texture);
  glTexParameteri(target, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(target, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  return texture;
}

}  // namespace

SpectralAlbedo::SpectralAlbedo() {
  constexpr int res = kRgbToSpectrumRes;
  coefficients_ = nearest_texture(GL_TEXTURE_3D);
  // The table's layout is the texture's: cell (l, k, j, i) is texel (i, j, res l + k).
  glTexImage3D(GL_TEXTURE_3D, 0, GL_RGB32F, res, res, 3 * res, 0, GL_RGB, GL_FLOAT,
               detail::rgb_to_spectrum_table(0, 0, 0));
  // The CIE functions as linear sRGB over the integral of y-bar (the sum of spectrum times row
  // is then the colour's linear sRGB: the conversion is linear), and ln(lambda) beside them, so
  // that the shader's sum takes no logarithm per wavelength.
  std::vector<float> rows;
  rows.reserve(4 * kCieTableSize);
  const double n = 1.0 / cie_y_integral();
  for (int i = 0; i < kCieTableSize; ++i) {
    const double* c = cie_data::kXyzBar1931[i];
    const LinearRgb rgb = linear_srgb_from_xyz({c[0] * n, c[1] * n, c[2] * n});
    rows.insert(rows.end(),
                {static_cast<float>(rgb.r), static_cast<float>(rgb.g), static_cast<float>(rgb.b),
                 static_cast<float>(std::log(kCieMinWavelength + i))});
  }
  cie_ = nearest_texture(GL_TEXTURE_2D);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, kCieTableSize, 1, 0, GL_RGBA, GL_FLOAT, rows.data());
  spectra_ = nearest_texture(GL_TEXTURE_2D);
  check_gl("uploading the spectral albedo tables");
}

void SpectralAlbedo::cover(const std::vector<const Image*>& images) {
#ifdef __EMSCRIPTEN__
  const auto rgb = [](const Rgb& t) { return LinearRgb{t.r, t.g, t.b}; };  // linear already
  const float* table = nullptr;
  std::array<RgbToSpectrumCells, 3> cells;
  for (const Image* image : images) {
    if (!covered_.insert(image).second) continue;
    for (int y = 0; y < image->height; ++y)
      for (int x = 0; x < image->width; ++x) {
        const int x1 = (x + 1) % image->width, y1 = (y + 1) % image->height;
        const LinearRgb block[4] = {rgb(image->texel(x, y)), rgb(image->texel(x1, y)),
                                    rgb(image->texel(x, y1)), rgb(image->texel(x1, y1))};
        const int n = rgb_to_spectrum_cells_of_blends(block, cells);
        for (int c = 0; c < n; ++c)
          for (int j = cells[c].j0; j <= cells[c].j1; ++j)
            for (int i = cells[c].i0; i <= cells[c].i1; ++i)
              table = detail::rgb_to_spectrum_table(cells[c].l, j, i);
      }
  }
  if (!table) return;
  constexpr int res = kRgbToSpectrumRes;
  glBindTexture(GL_TEXTURE_3D, coefficients_);
  glTexImage3D(GL_TEXTURE_3D, 0, GL_RGB32F, res, res, 3 * res, 0, GL_RGB, GL_FLOAT, table);
  check_gl("uploading the fitted coefficients");
#else
  (void)images;
#endif
}

SpectralAlbedo::~SpectralAlbedo() {
  const GLuint textures[] = {coefficients_, cie_, spectra_};
  glDeleteTextures(3, textures);
}

void SpectralAlbedo::prepare(const Lighting& lighting, std::size_t light_count,
                             double lowest_log_total, double highest_log_total) {
  lowest_ = lowest_log_total - kLogMargin;
  highest_ = highest_log_total + kLogMargin;
  prepared_ = true;
  const double first = std::log(kCieMinWavelength) + lowest_;
  const double last = std::log(kCieMaxWavelength) + highest_;
  const int samples = static_cast<int>(std::ceil((last - first) * kSamplesPerLogUnit)) + 2;
  const int rows = (samples + kRowTexels - 1) / kRowTexels;
  const std::size_t lights = std::max<std::size_t>(light_count, 1);
  std::vector<float> texels(lights * static_cast<std::size_t>(rows) * kRowTexels, 0.0f);
  for (std::size_t l = 0; l < light_count; ++l) {
    float* row = &texels[l * static_cast<std::size_t>(rows) * kRowTexels];
    for (int j = 0; j < samples; ++j)
      row[j] =
          static_cast<float>(lighting.light_spectral(l, std::exp(first + j / kSamplesPerLogUnit)));
  }
  glBindTexture(GL_TEXTURE_2D, spectra_);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, kRowTexels, static_cast<GLsizei>(lights) * rows, 0,
               GL_RED, GL_FLOAT, texels.data());
  check_gl("uploading the lights' spectra");
  grid_[0] = static_cast<float>(first);
  grid_[1] = static_cast<float>(kSamplesPerLogUnit);
  grid_[2] = static_cast<float>(kRowTexels);
  grid_[3] = static_cast<float>(rows);
}

namespace {
constexpr const char* kSamplers[] = {"rgb_to_spectrum", "cie_srgb", "light_spectra"};
}

void SpectralAlbedo::assign_units(GLuint program, int first_unit) {
  for (int k = 0; k < 3; ++k) glUniform1i(uniform(program, kSamplers[k]), first_unit + k);
}

void SpectralAlbedo::bind(GLuint program, int first_unit) const {
  const GLuint textures[] = {coefficients_, cie_, spectra_};
  const GLenum targets[] = {GL_TEXTURE_3D, GL_TEXTURE_2D, GL_TEXTURE_2D};
  for (int k = 0; k < 3; ++k) {
    glActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + first_unit + k));
    glBindTexture(targets[k], textures[k]);
  }
  glActiveTexture(GL_TEXTURE0);
  assign_units(program, first_unit);
  glUniform4f(uniform(program, "light_spectra_grid"), grid_[0], grid_[1], grid_[2], grid_[3]);
}

}  // namespace lightcone
