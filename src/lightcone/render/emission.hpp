// What a surface point or sky direction emits in its own rest frame: its colour at rest and its
// spectral radiance at every wavelength (for the spectral Doppler model).
#pragma once

#include <variant>
#include <vector>

#include "lightcone/color/cie.hpp"
#include "lightcone/color/rgb_spectrum.hpp"
#include "lightcone/color/spectrum.hpp"
#include "lightcone/render/tracer.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

struct PointEmission {
  LinearRgb rest_rgb;  // the colour at D = 1
  std::variant<RgbIlluminantSpectrum, BlackbodySpectrum, const TabulatedSpectrum*> spectrum;
  // For emitters fixed per material: the spectrum at every nm of [360, 830], so that the
  // renderer's unshifted wavelengths cost a lookup (null: evaluate).
  const double* visible_table = nullptr;

  double spectral_radiance(double lambda_nm) const;
  // The same, through the visible table where there is one and lambda is in [360, 830] nm.
  // The renderer evaluates both the shifted and the unshifted wavelengths with it, so that at
  // D = 1 the two agree bit for bit and a scene at rest shows exactly its rest colours.
  double fast_spectral_radiance(double lambda_nm) const;
};

// The emission of every object's material and of the sky, prepared once per render: the
// spectra of fixed colours are fitted once, not per ray. Textures and sky images are fitted per
// lookup, and only when `spectral` asks for spectra.
class EmissionTable {
 public:
  EmissionTable(const Scene& scene, bool spectral);
  EmissionTable(const EmissionTable&) = delete;  // emissions point into its tables
  EmissionTable& operator=(const EmissionTable&) = delete;

  PointEmission surface(std::size_t object_index, const Hit& hit) const;
  PointEmission sky(const Vec3& pattern_direction) const;

 private:
  PointEmission from_rgb(const Rgb& rgb) const;
  // Fixed emissions of one material (solid: [0]; checker: both; blackbody, spectrum: [0]).
  struct Fixed {
    PointEmission colours[2];
  };
  Fixed prepare(const Material& material);

  // Fills the visible table of a fixed emission (storage in tables_).
  void tabulate(PointEmission& emission);

  const Scene& scene_;
  bool spectral_;
  std::vector<TabulatedSpectrum> tabulated_;  // reserved up front: PointEmission points here
  std::vector<std::vector<double>> tables_;   // visible tables; inner buffers never move
  std::vector<Fixed> objects_;
  Fixed sky_;
};

}  // namespace lightcone
