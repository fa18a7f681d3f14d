#include "lightcone/frame/emission.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>
#include <string>

#include "lightcone/color/spectrum.hpp"
#include "lightcone/frame/camera_model.hpp"
#include "lightcone/frame/shading.hpp"
#include "lightcone/portable.hpp"

namespace lightcone {
namespace {

LinearRgb linear(const Rgb& c) {
  return {c.r, c.g, c.b};
}

bool has_per_lookup_colours(const Scene& scene) {
  if (std::holds_alternative<SkyImage>(scene.sky.pattern)) return true;
  for (const Object& o : scene.objects)
    if (o.material.unlit && std::holds_alternative<Texture>(o.material.pattern)) return true;
  return false;
}

PointEmission lit_colour(const Rgb& albedo, int fixed_colour) {
  PointEmission e;
  e.rest_rgb = linear(albedo);
  e.fixed_colour = fixed_colour;
  return e;
}

}  // namespace

LogDopplerRange visible_log_doppler(const ResolvedScene& scene, bool lit) {
  LogDopplerRange range;
  if (!scene.scene->render.relativity) return range;
  // A bound that is not finite is refused: std::min and std::max would drop a NaN silently,
  // and the colour tables would miss that body's factors.
  // `object`: the body's (nullptr: the sky's).
  const auto include = [&](double lo, double hi, const Object* object) {
    if (!(std::isfinite(lo) && std::isfinite(hi)))
      throw std::logic_error("the Doppler factors with which " +
                             (object ? "object \"" + object->name + "\"" : std::string("the sky")) +
                             " is seen have no finite bound");
    range.lo = range.empty ? lo : std::min(range.lo, lo);
    range.hi = range.empty ? hi : std::max(range.hi, hi);
    range.empty = false;
  };
  // D depends on the look direction u only through dot(u, velocity), and falls as it grows: its
  // extremes over the image are at the directions where that product is extreme.
  // A spinning body's points move relative to it with rapidity up to that of its rim, which
  // moves their ln D by as much at most.
  const auto add = [&](const Vec3& v, double spread, const Object* object) {
    const ViewExtremes e = view_extremes_along(scene.camera, v);
    include(std::log(scene.doppler(e.largest, v)) - spread,
            std::log(scene.doppler(e.smallest, v)) + spread, object);
  };
  if (scene.hole) {
    // Near a hole the sky, the disk and the bodies are seen along curved rays, with the shift g.
    if (!lit) {
      const LogShiftRange r = sky_log_shift_range(*scene.hole);
      include(r.lo, r.hi, nullptr);
    }
    for (const ResolvedBody& b : scene.bodies)
      if (b.object->material.unlit != lit) {
        const LogShiftRange r = body_log_shift_range(*scene.hole, *b.object);
        include(r.lo, r.hi, b.object);
      }
    return range;
  }
  if (!lit) add(scene.sky_velocity, 0, nullptr);
  for (const ResolvedBody& b : scene.bodies)
    if (b.object->material.unlit != lit)
      add(b.velocity, b.spin >= 0 ? spin_rapidity(scene.spins[b.spin]) : 0.0, b.object);
  return range;
}

const EmissionTable& EmissionTable::keep(std::unique_ptr<EmissionTable>& kept,
                                         const ResolvedScene& scene) {
  if (!kept || !kept->serves(scene)) {
    kept.reset();  // (the old tables go before the new are built)
    kept = std::make_unique<EmissionTable>(scene, kKeptMargin);
  }
  return *kept;
}

EmissionTable::EmissionTable(const ResolvedScene& resolved, double margin)
    : scene_(*resolved.scene),
      serial_([] {
        static std::atomic<std::uint64_t> made{0};
        return ++made;
      }()),
      spectral_(resolved.scene->render.doppler == DopplerModel::kSpectral),
      range_([&] {
        LogDopplerRange r = visible_log_doppler(resolved, false);
        r.lo -= margin;
        r.hi += margin;
        return r;
      }()),
      grid_(DopplerGrid::reaching(range_.lo, range_.hi, rgb_emitter_zero_wavelength())) {
  if (spectral_) {
    illuminant_ = illuminant_samples([](double l) { return reference_illuminant(l); }, grid_,
                                     ParallelNodes{});
    white_ = DopplerXyzTable::under([](double l) { return rgb_white_factor(l); }, illuminant_,
                                    grid_, ParallelNodes{});
    nodes_.resize(static_cast<std::size_t>(kRgbEmitterCases) * kRgbToSpectrumRes);
    node_built_.assign(nodes_.size(), false);
    if (has_per_lookup_colours(scene_)) {
      parallel_for(std::size_t{0}, nodes_.size(), [&](std::size_t i) {
        const int node_case = static_cast<int>(i) / kRgbToSpectrumRes;
        const int node = static_cast<int>(i) % kRgbToSpectrumRes;
        nodes_[i] = DopplerXyzTable::under(rgb_emitter_node(node_case, node), illuminant_, grid_);
      });
      node_built_.assign(nodes_.size(), true);
    }
  }
  objects_.reserve(scene_.objects.size());
  for (const Object& o : scene_.objects) objects_.push_back(prepare(o.material));
  if (resolved.hole && resolved.hole->disk) disk_ = thermal_disk(*resolved.hole);
  if (const auto* c = std::get_if<SolidColor>(&scene_.sky.pattern)) {
    sky_.colours[0] = fixed_rgb(c->color);
  } else if (const auto* g = std::get_if<SkyGrid>(&scene_.sky.pattern)) {
    sky_.colours[0] = fixed_rgb(g->background);
    sky_.colours[1] = fixed_rgb(g->line_color);
  }
}

bool EmissionTable::serves(const ResolvedScene& next) const {
  // (The same Scene has a hole both times or neither.)
  if (&scene_ != next.scene || next.hole ||
      spectral_ != (next.scene->render.doppler == DopplerModel::kSpectral))
    return false;
  const LogDopplerRange r = visible_log_doppler(next, false);
  return range_.lo <= r.lo && r.hi <= range_.hi;
}

// The disk's hottest ring, tabulated in every colour model (the others need its colour at rest
// at each temperature): over the factors s = g T / T_peak it is read at, down to the floor below
// which a blackbody gives no visible light worth a bit of the image.
ThermalEmission EmissionTable::thermal_disk(const HoleView& hole) {
  const AccretionDisk& disk = *hole.disk;
  ThermalEmission t;
  t.floor = std::min(kThermalFloorKelvin / disk.temperature_k, 1.0);
  const LogShiftRange g = disk_log_shift_range(hole);
  // s = tau g with tau in [floor, 1]; the non-spectral models read tau alone.
  const DopplerGrid grid =
      DopplerGrid::covering(std::log(t.floor) + std::min(g.lo, 0.0), std::max(g.hi, 0.0));
  const BlackbodySpectrum peak =
      BlackbodySpectrum::with_luminance(disk.temperature_k, disk.luminance);
  t.peak.rest_rgb = linear_srgb_from_xyz(xyz_from_spectrum(peak));
  t.peak.tables[0] = &fixed_tables_.emplace_back(DopplerXyzTable::of(peak, grid, ParallelNodes{}));
  t.peak.weights[0] = 1;
  t.peak.table_count = 1;
  return t;
}

const DopplerXyzTable& EmissionTable::node_table(int node_case, int node) {
  const std::size_t i = static_cast<std::size_t>(node_case) * kRgbToSpectrumRes + node;
  if (!node_built_[i]) {
    nodes_[i] = DopplerXyzTable::under(rgb_emitter_node(node_case, node), illuminant_, grid_,
                                       ParallelNodes{});
    node_built_[i] = true;
  }
  return nodes_[i];
}

template <class Spectrum>
PointEmission EmissionTable::fixed_spectrum(const Spectrum& spectrum) {
  PointEmission e;
  e.rest_rgb = linear_srgb_from_xyz(xyz_from_spectrum(spectrum));
  if (spectral_) {
    const DopplerGrid grid = DopplerGrid::reaching(range_.lo, range_.hi, spectrum.constant_below());
    e.tables[0] = &fixed_tables_.emplace_back(DopplerXyzTable::of(spectrum, grid, ParallelNodes{}));
    e.weights[0] = 1;
    e.table_count = 1;
  }
  return e;
}

template <class MakeSpectrum>
PointEmission EmissionTable::shared_spectrum(std::vector<double> key, const MakeSpectrum& make) {
  if (const auto it = spectrum_emissions_.find(key); it != spectrum_emissions_.end())
    return it->second;
  const PointEmission e = fixed_spectrum(make());
  spectrum_emissions_.emplace(std::move(key), e);
  return e;
}

PointEmission EmissionTable::fixed_rgb(const Rgb& rgb) {
  PointEmission e;
  e.rest_rgb = linear(rgb);
  if (!spectral_) return e;
  // Objects of one colour share its table.
  const std::array<float, 3> key{rgb.r, rgb.g, rgb.b};
  if (const auto it = rgb_tables_.find(key); it != rgb_tables_.end()) {
    e.tables[0] = it->second;
    e.weights[0] = 1;
    e.table_count = 1;
    return e;
  }
  const RgbEmitterSpectrum s = RgbEmitterSpectrum::from_rgb(e.rest_rgb);
  const DopplerXyzTable* a = nullptr;
  const DopplerXyzTable* b = nullptr;
  if (s.scale > 0) {
    a = &node_table(s.node_case, s.node);
    b = &node_table(s.node_case, s.node + 1);
  }
  // Past a thousand distinct colours a table each (some 6 KB) would cost more memory than it
  // saves time (a quarter of the peak memory of 10^5 bodies of distinct colours at 4,096
  // tables): the rest combine the white's and the two nodes' tables per lookup.
  if (rgb_tables_.size() >= kMaxColourTables) {
    e.tables[0] = &white_;
    e.weights[0] = s.grey;
    e.table_count = 1;
    if (a) {
      e.tables[1] = a;
      e.tables[2] = b;
      e.weights[1] = s.scale * (1 - s.blend);
      e.weights[2] = s.scale * s.blend;
      e.table_count = 3;
    }
    return e;
  }
  // The table of this colour's spectrum, combined node by node from the white's and the two
  // emitter nodes' tables (the spectrum is their weighted sum).
  std::vector<Xyz> nodes(grid_.size());
  for (int i = 0; i < grid_.size(); ++i) {
    const Xyz w = white_.node(i);
    Xyz c{s.grey * w.x, s.grey * w.y, s.grey * w.z};
    if (a) {
      const double wa = s.scale * (1 - s.blend), wb = s.scale * s.blend;
      c.x += wa * a->node(i).x + wb * b->node(i).x;
      c.y += wa * a->node(i).y + wb * b->node(i).y;
      c.z += wa * a->node(i).z + wb * b->node(i).z;
    }
    nodes[i] = c;
  }
  e.tables[0] = &fixed_tables_.emplace_back(grid_, std::move(nodes));
  e.weights[0] = 1;
  e.table_count = 1;
  rgb_tables_.emplace(key, e.tables[0]);
  return e;
}

PointEmission EmissionTable::per_lookup_rgb(const Rgb& rgb) const {
  PointEmission e;
  e.rest_rgb = linear(rgb);
  if (!spectral_) return e;
  const RgbEmitterSpectrum s = RgbEmitterSpectrum::from_rgb(e.rest_rgb);
  e.tables[0] = &white_;
  e.weights[0] = s.grey;
  e.table_count = 1;
  if (s.scale > 0) {
    const std::size_t base = static_cast<std::size_t>(s.node_case) * kRgbToSpectrumRes + s.node;
    e.tables[1] = &nodes_[base];
    e.tables[2] = &nodes_[base + 1];
    e.weights[1] = s.scale * (1 - s.blend);
    e.weights[2] = s.scale * s.blend;
    e.table_count = 3;
  }
  return e;
}

EmissionTable::Fixed EmissionTable::prepare(const Material& m) {
  Fixed f;
  Rgb colours[2];
  const int count = pattern_colours(m, colours);
  for (int k = 0; k < count; ++k)
    f.colours[k] = m.unlit ? fixed_rgb(colours[k]) : lit_colour(colours[k], k);
  if (const auto* b = std::get_if<Blackbody>(&m.pattern)) {
    f.colours[0] = shared_spectrum({0, b->temperature_k, b->luminance}, [b] {
      return BlackbodySpectrum::with_luminance(b->temperature_k, b->luminance);
    });
  } else if (const auto* s = std::get_if<EmissionSpectrum>(&m.pattern)) {
    std::vector<double> key{1, static_cast<double>(s->wavelengths_nm.size())};
    key.insert(key.end(), s->wavelengths_nm.begin(), s->wavelengths_nm.end());
    key.insert(key.end(), s->values.begin(), s->values.end());
    f.colours[0] = shared_spectrum(std::move(key), [s] {
      return TabulatedSpectrum{s->wavelengths_nm, s->values};
    });
  }
  return f;
}

PointEmission EmissionTable::surface(std::size_t object_index, const Hit& hit) const {
  const Material& m = scene_.objects[object_index].material;
  const Fixed& f = objects_[object_index];
  if (const auto* ch = std::get_if<Checker>(&m.pattern))
    return f.colours[checker_index(*ch, hit.shape_point)];
  if (const auto* b = std::get_if<Blink>(&m.pattern))
    return f.colours[blink_index(*b, hit.proper_time)];
  if (const auto* c = std::get_if<Clock>(&m.pattern))
    return f.colours[clock_index(*c, hit.uv, hit.proper_time)];
  if (const auto* t = std::get_if<Texture>(&m.pattern)) {
    const Rgb c = texture_colour(*t, hit);
    return m.unlit ? per_lookup_rgb(c) : PointEmission{linear(c)};
  }
  return f.colours[0];
}

PointEmission EmissionTable::sky(const Vec3& d) const {
  if (const auto* g = std::get_if<SkyGrid>(&scene_.sky.pattern))
    return sky_.colours[on_grid_line(*g, d) ? 1 : 0];
  if (const auto* i = std::get_if<SkyImage>(&scene_.sky.pattern))
    return per_lookup_rgb(sky_image_colour(*i, d));
  return sky_.colours[0];
}

const PointEmission* EmissionTable::uniform_sky() const {
  return std::holds_alternative<SolidColor>(scene_.sky.pattern) ? &sky_.colours[0] : nullptr;
}

}  // namespace lightcone
