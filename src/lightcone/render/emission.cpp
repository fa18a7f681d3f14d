#include "lightcone/render/emission.hpp"

#include "lightcone/render/shading.hpp"

namespace lightcone {
namespace {

// The rest colour of a spectrum: its XYZ by the 1 nm quadrature, in linear sRGB.
template <class Spectrum>
LinearRgb rest_colour(const Spectrum& spectrum) {
  return linear_srgb_from_xyz(xyz_from_spectrum(spectrum));
}

}  // namespace

double PointEmission::spectral_radiance(double lambda_nm) const {
  struct Visitor {
    double lambda;
    double operator()(const RgbIlluminantSpectrum& s) const { return s(lambda); }
    double operator()(const BlackbodySpectrum& s) const { return s(lambda); }
    double operator()(const TabulatedSpectrum* s) const { return (*s)(lambda); }
  };
  return std::visit(Visitor{lambda_nm}, spectrum);
}

double PointEmission::fast_spectral_radiance(double lambda_nm) const {
  if (!visible_table) return spectral_radiance(lambda_nm);
  const double position = lambda_nm - kCieMinWavelength;
  const auto i = static_cast<std::size_t>(position);
  if (!(position >= 0) || i + 1 >= static_cast<std::size_t>(kCieTableSize))
    return spectral_radiance(lambda_nm);
  const double f = position - static_cast<double>(i);
  return visible_table[i] + f * (visible_table[i + 1] - visible_table[i]);
}

void EmissionTable::tabulate(PointEmission& emission) {
  if (!spectral_) return;
  std::vector<double>& table = tables_.emplace_back(kCieTableSize);
  for (int i = 0; i < kCieTableSize; ++i)
    table[i] = emission.spectral_radiance(kCieMinWavelength + i);
  emission.visible_table = table.data();
}

EmissionTable::EmissionTable(const Scene& scene, bool spectral)
    : scene_(scene), spectral_(spectral) {
  std::size_t tables = 0;
  for (const Object& o : scene.objects)
    tables += std::holds_alternative<EmissionSpectrum>(o.material.pattern) ? 1 : 0;
  tabulated_.reserve(tables);
  objects_.reserve(scene.objects.size());
  for (const Object& o : scene.objects) objects_.push_back(prepare(o.material));
  if (const auto* c = std::get_if<SolidColor>(&scene.sky.pattern)) {
    sky_.colours[0] = from_rgb(c->color);
  } else if (const auto* g = std::get_if<SkyGrid>(&scene.sky.pattern)) {
    sky_.colours[0] = from_rgb(g->background);
    sky_.colours[1] = from_rgb(g->line_color);
  }
  for (Fixed& f : objects_)
    for (PointEmission& e : f.colours) tabulate(e);
  for (PointEmission& e : sky_.colours) tabulate(e);
}

PointEmission EmissionTable::from_rgb(const Rgb& c) const {
  PointEmission e;
  e.rest_rgb = {c.r, c.g, c.b};
  if (spectral_) e.spectrum = RgbIlluminantSpectrum::from_rgb(e.rest_rgb);
  return e;
}

EmissionTable::Fixed EmissionTable::prepare(const Material& m) {
  Fixed f;
  if (const auto* c = std::get_if<SolidColor>(&m.pattern)) {
    f.colours[0] = from_rgb(c->color);
  } else if (const auto* ch = std::get_if<Checker>(&m.pattern)) {
    f.colours[0] = from_rgb(ch->colors[0]);
    f.colours[1] = from_rgb(ch->colors[1]);
  } else if (const auto* b = std::get_if<Blackbody>(&m.pattern)) {
    const auto spectrum = BlackbodySpectrum::with_luminance(b->temperature_k, b->luminance);
    f.colours[0].rest_rgb = rest_colour(spectrum);
    f.colours[0].spectrum = spectrum;
  } else if (const auto* s = std::get_if<EmissionSpectrum>(&m.pattern)) {
    tabulated_.push_back({s->wavelengths_nm, s->values});
    f.colours[0].rest_rgb = rest_colour(tabulated_.back());
    f.colours[0].spectrum = &tabulated_.back();
  }
  return f;
}

PointEmission EmissionTable::surface(std::size_t object_index, const Hit& hit) const {
  const Material& m = scene_.objects[object_index].material;
  const Fixed& f = objects_[object_index];
  if (const auto* ch = std::get_if<Checker>(&m.pattern))
    return f.colours[checker_index(*ch, hit.shape_point)];
  if (const auto* t = std::get_if<Texture>(&m.pattern)) return from_rgb(texture_colour(*t, hit));
  return f.colours[0];
}

PointEmission EmissionTable::sky(const Vec3& d) const {
  if (const auto* g = std::get_if<SkyGrid>(&scene_.sky.pattern))
    return sky_.colours[on_grid_line(*g, d) ? 1 : 0];
  if (const auto* i = std::get_if<SkyImage>(&scene_.sky.pattern))
    return from_rgb(sky_image_colour(*i, d));
  return sky_.colours[0];
}

}  // namespace lightcone
