// What a surface point or sky direction emits in its own rest frame: its colour at rest and,
// for the spectral model, how that colour changes with the Doppler factor (tabulated per render,
// docs/design/spectral.md).
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <vector>

#include "lightcone/color/cie.hpp"
#include "lightcone/color/doppler_table.hpp"
#include "lightcone/color/rgb_spectrum.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/frame/surface_hit.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

struct PointEmission {
  LinearRgb rest_rgb;  // the colour at D = 1
  // Spectral model: the colour seen with factor D, before the searchlight factor, is
  // sum over k < table_count of weights[k] * tables[k](D).
  std::array<const DopplerXyzTable*, 3> tables{};
  std::array<double, 3> weights{};
  int table_count = 0;
  // For lit materials (rest_rgb is the albedo): which fixed colour of the material it is (0,
  // or 1 for a checker's second), or -1 for a colour looked up per hit (textures).
  int fixed_colour = -1;

  Xyz seen_with_doppler(double d) const {
    if (table_count == 0) return {};
    const GridPosition position = grid_position(tables[0]->grid(), d);
    Xyz sum;
    for (int k = 0; k < table_count; ++k) {
      const Xyz c = (*tables[k])(position);
      sum.x += weights[k] * c.x;
      sum.y += weights[k] * c.y;
      sum.z += weights[k] * c.z;
    }
    return sum;
  }
  // linear_srgb_from_xyz(seen_with_doppler(d)), by the tables' own sRGB cubics.
  LinearRgb rgb_seen_with_doppler(double d) const {
    if (table_count == 0) return {};
    const GridPosition position = grid_position(tables[0]->grid(), d);
    if (table_count == 1) {  // (most colours: a table of their own, weight 1)
      const LinearRgb c = tables[0]->rgb(position);
      return {weights[0] * c.r, weights[0] * c.g, weights[0] * c.b};
    }
    LinearRgb sum;
    for (int k = 0; k < table_count; ++k) {
      const LinearRgb c = tables[k]->rgb(position);
      sum.r += weights[k] * c.r;
      sum.g += weights[k] * c.g;
      sum.b += weights[k] * c.b;
    }
    return sum;
  }
};

// A blackbody whose temperature varies over the emitter (the accretion disk): the emission of
// its hottest part, tabulated against s from `floor` up, and the colour of a part at tau times
// that temperature is received_thermal_colour's. Below the floor (tau g < floor, a blackbody at
// under kThermalFloorKelvin) it is taken as black.
inline constexpr double kThermalFloorKelvin = 300;
struct ThermalEmission {
  PointEmission peak;
  double floor = 0;
};

// The range of ln D with which the camera sees the lit bodies (`lit`), or the emitters and the
// sky, over every direction of its image, edges included (0 for the classical picture): exact,
// from the directions where each velocity's D is extreme (view_extremes_along).
struct LogDopplerRange {
  double lo = 0, hi = 0;
  bool empty = true;  // nothing of the kind is seen (lo = hi = 0)
};
LogDopplerRange visible_log_doppler(const ResolvedScene& scene, bool lit);

// The emission of every object's material and of the sky, prepared once per render. For the
// spectral model every fixed colour gets its own table against ln D, up to kMaxColourTables
// distinct colours; the colours past them, textures and sky images are combined per lookup
// from the tables of the RGB white and the emitter nodes (RgbEmitterSpectrum); all the node
// tables are built when the scene has textures or sky images, those used otherwise.
class EmissionTable {
 public:
  static constexpr std::size_t kMaxColourTables = 1024;
  // The margin of tables kept from frame to frame (the viewer's, and the lights' in the raster
  // renderer): a camera speeding up reuses them for a while.
  static constexpr double kKeptMargin = 0.25;

  // `margin`: the tables cover the factors the scene is seen with widened by this much of ln D
  // on each side, so that a renderer can keep them for the next frames (serves()).
  explicit EmissionTable(const ResolvedScene& scene, double margin = 0);
  EmissionTable(const EmissionTable&) = delete;  // emissions point into its tables
  EmissionTable& operator=(const EmissionTable&) = delete;

  // Whether these tables are those `next` would build, but for their range: the same Scene
  // object (so the same materials and sky; a viewer keeps one and changes only its camera and
  // render settings), the same colour model, no black hole (its disk's table follows the
  // camera), and every factor `next` is seen with inside the tables' range.
  bool serves(const ResolvedScene& next) const;
  // The tables a renderer keeps from frame to frame (the viewer's): `kept` while it serves
  // `scene`, else built anew over kKeptMargin (the old freed first).
  static const EmissionTable& keep(std::unique_ptr<EmissionTable>& kept,
                                   const ResolvedScene& scene);
  // Unique to these tables within the process (a new set may take a freed one's address), so
  // that a renderer which tabulated colours from a set can tell whether it is handed that one.
  std::uint64_t serial() const { return serial_; }

  PointEmission surface(std::size_t object_index, const Hit& hit) const;
  PointEmission sky(const Vec3& pattern_direction) const;
  // The sky's emission where it is the same in every direction (a solid colour), else null.
  const PointEmission* uniform_sky() const;
  // The fixed colours of a material (0, or 1 for a checker's second) and of the sky (a grid's
  // line colour is 1), for a renderer that tabulates them.
  const PointEmission& object_colour(std::size_t object_index, int colour) const {
    return objects_[object_index].colours[colour];
  }
  const PointEmission& sky_colour(int colour) const { return sky_.colours[colour]; }
  // The black hole's accretion disk (a scene with one).
  const ThermalEmission& disk() const { return disk_; }
  // The tables that colours looked up per hit combine (spectral model; the nodes are built
  // when the scene has textured emitters or a sky image): the RGB white's and node `node` of
  // emitter case `node_case` (RgbEmitterSpectrum).
  const DopplerXyzTable& white_table() const { return white_; }
  const DopplerXyzTable& emitter_node_table(int node_case, int node) const {
    return nodes_[static_cast<std::size_t>(node_case) * kRgbToSpectrumRes + node];
  }

 private:
  struct Fixed {
    PointEmission colours[2];
  };
  Fixed prepare(const Material& material);
  PointEmission fixed_rgb(const Rgb& rgb);
  ThermalEmission thermal_disk(const HoleView& hole);
  template <class Spectrum>
  PointEmission fixed_spectrum(const Spectrum& spectrum);
  // Bodies of one spectrum share its table: `key` holds the spectrum's parameters.
  template <class MakeSpectrum>
  PointEmission shared_spectrum(std::vector<double> key, const MakeSpectrum& make);
  // Per lookup (textures, sky images): the white and node tables, weighted.
  PointEmission per_lookup_rgb(const Rgb& rgb) const;
  const DopplerXyzTable& node_table(int node_case, int node);

  const Scene& scene_;
  std::uint64_t serial_;
  bool spectral_;
  // The factors the scene is seen with, margin included (ln D), and the grid of the RGB
  // emitters' tables over them (blackbodies and tabulated spectra get grids of their own,
  // reaching where each is constant).
  LogDopplerRange range_;
  DopplerGrid grid_;
  std::vector<double> illuminant_;  // the reference illuminant on the grid (illuminant_samples)
  DopplerXyzTable white_;
  std::vector<DopplerXyzTable> nodes_;  // kRgbEmitterCases * kRgbToSpectrumRes, built on demand
  std::vector<bool> node_built_;
  std::deque<DopplerXyzTable> fixed_tables_;                           // stable addresses
  std::map<std::array<float, 3>, const DopplerXyzTable*> rgb_tables_;  // one per distinct colour
  std::map<std::vector<double>, PointEmission> spectrum_emissions_;    // one per distinct spectrum
  std::vector<Fixed> objects_;
  Fixed sky_;
  ThermalEmission disk_;
};

}  // namespace lightcone
