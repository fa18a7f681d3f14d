// Lit textures under the spectral model, for the raster renderer: what lighting.glsl needs to
// colour a texel as the tracer does, fitting its albedo to a reflectance spectrum per sample
// (rgb_to_sigmoid) and summing its light nanometre by nanometre
// (xyz_of_reflection_seen_with_doppler): the coefficient table, the CIE functions, and each
// light's spectrum tabulated against ln(lambda) over the wavelengths the frame's Doppler factors
// reach (docs/design/raster.md, "Differences from the ray tracer").
#pragma once

#include <set>
#include <vector>

#include "lightcone/frame/lighting.hpp"
#include "lightcone/raster/gl.hpp"

namespace lightcone {

// The first of the three texture units the tables take.
inline constexpr int kSpectralAlbedoUnit = 9;

class SpectralAlbedo {
 public:
  // Uploads the coefficient table and the CIE functions (once).
  SpectralAlbedo();
  ~SpectralAlbedo();
  SpectralAlbedo(const SpectralAlbedo&) = delete;
  SpectralAlbedo& operator=(const SpectralAlbedo&) = delete;

  // The lights' spectra for a frame whose camera-to-surface and surface-to-light factors
  // multiply to between e^lowest_log_total and e^highest_log_total, tabulated kLogMargin wider
  // on each side so that the next frames of a moving camera can keep them.
  void prepare(const Lighting& lighting, std::size_t light_count, double lowest_log_total,
               double highest_log_total);
  // Whether the lights' spectra as last prepared cover those products.
  bool covers(double lowest_log_total, double highest_log_total) const {
    return prepared_ && lowest_log_total >= lowest_ && highest_log_total <= highest_;
  }
  static constexpr double kLogMargin = 0.25;
  // Where the coefficient table is fitted column by column as it is needed (the browser's
  // page: rgb_spectrum.hpp's detail::rgb_to_spectrum_table), fits every column the lit
  // textures' lookups may read (each 2 x 2 block of texels blended), once per image, and
  // uploads the table again if any image was new. Elsewhere the whole table is there and this
  // does nothing.
  void cover(const std::vector<const Image*>& images);
  // Binds the tables to texture units first_unit .. first_unit + 2 for `program` (in use).
  void bind(GLuint program, int first_unit) const;
  // Points `program`'s samplers of the tables at those units, without the tables.
  static void assign_units(GLuint program, int first_unit);

 private:
  GLuint coefficients_ = 0, cie_ = 0, spectra_ = 0;
  float grid_[4] = {0, 1, 1, 1};  // lighting.glsl's light_spectra_grid
  bool prepared_ = false;
  double lowest_ = 0, highest_ = 0;  // the products of factors the spectra cover
  std::set<const Image*> covered_;   // the images cover() has fitted the columns of
};

}  // namespace lightcone
