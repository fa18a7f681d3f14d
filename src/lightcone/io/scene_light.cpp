#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "lightcone/io/scene_reader.hpp"
#include "lightcone/io/star_catalogue.hpp"

namespace lightcone::scene_io {

Material SceneReader::material(const Node& n, std::size_t index) {
  const std::string_view kind =
      one_of(n, {"color", "checker", "texture", "blackbody", "spectrum", "blink", "clock"},
             {"unlit", "glossy"});
  Material m;
  const Node unlit = member(n, "unlit");
  if (unlit.value) m.unlit = boolean(unlit);
  if (!m.unlit && (kind == "blackbody" || kind == "spectrum"))
    fail(unlit, fmt::format("a {} material is an emitter and cannot be lit (a lit material's "
                            "albedo is a color, checker or texture)",
                            kind));
  if (Node glossy = member(n, "glossy"); glossy.value) {
    if (m.unlit) fail(glossy, "a glossy layer needs a lit material (\"unlit\": false)");
    m.glossy = glossy_layer(glossy);
  }
  // A lit surface reflects a fraction of the light: its colours are albedos, in [0, 1].
  auto surface_color = [&](const Node& c) { return m.unlit ? color(c) : albedo(c); };
  const Node body = member(n, kind);
  if (kind == "color") {
    m.pattern = SolidColor{surface_color(body)};
  } else if (kind == "checker") {
    object(body, {"size", "colors"});
    Checker checker;
    checker.size = positive(member(body, "size"));
    const Node colors = member(body, "colors");
    if (!need(colors).is_array() || colors.value->size() != 2)
      fail(colors, fmt::format("must be an array of 2 colours, got {}", describe(*colors.value)));
    checker.colors[0] = surface_color(element(colors, 0));
    checker.colors[1] = surface_color(element(colors, 1));
    m.pattern = checker;
  } else if (kind == "blink" || kind == "clock") {
    // Patterns on the body's own clock: a period of its proper time, two colours.
    const bool blink = kind == "blink";
    object(body, blink ? Names{"period", "duty", "colors"} : Names{"period", "colors"});
    const Node period = member(body, "period");
    const double p = positive(period) * c_;
    if (!std::isfinite(p)) fail(period, "must be finite");
    Rgb colors[2];
    const Node colors_node = member(body, "colors");
    if (colors_node.value) {
      if (!colors_node.value->is_array() || colors_node.value->size() != 2)
        fail(colors_node,
             fmt::format("must be an array of 2 colours, got {}", describe(*colors_node.value)));
      for (int k = 0; k < 2; ++k) colors[k] = surface_color(element(colors_node, k));
    }
    if (blink) {
      Blink b;
      b.period = p;
      if (Node duty = member(body, "duty"); duty.value) b.duty = in_range(duty, 0, 1);
      if (colors_node.value) std::copy(colors, colors + 2, b.colors);
      m.pattern = b;
    } else {
      Clock c;
      c.period = p;
      if (colors_node.value) std::copy(colors, colors + 2, c.colors);
      m.pattern = c;
      uv_patterns_.emplace_back(index, body.path());
    }
  } else if (kind == "blackbody") {
    object(body, {"temperature", "luminance"});
    Blackbody b;
    b.temperature_k = positive(member(body, "temperature"));
    if (Node y = member(body, "luminance"); y.value) b.luminance = non_negative(y);
    m.pattern = b;
  } else if (kind == "spectrum") {
    m.pattern = emission_spectrum(body);
  } else {
    assets_.push_back({Asset::kTexture, index, file_path(body), body.path()});
    uv_patterns_.emplace_back(index, body.path());
    m.pattern = Texture{};
  }
  return m;
}

Glossy SceneReader::glossy_layer(const Node& n) const {
  object(n, {"roughness", "specular"});
  Glossy g;
  if (Node r = member(n, "roughness"); r.value) g.roughness = in_range(r, 0, 1, true);
  if (Node f = member(n, "specular"); f.value) g.specular = in_range(f, 0, 1);
  return g;
}

Light SceneReader::read_light(const Node& n) const {
  const json& v = need(n);
  if (!v.is_object()) fail(n, fmt::format("must be an object, got {}", describe(v)));
  const Node type = member(n, "type");
  const std::string kind = string(type);
  std::vector<std::string_view> allowed = {"name",     "type",   "position", "time",
                                           "velocity", "motion", "color",    "blackbody"};
  if (kind == "point") {
    allowed.insert(allowed.end(), {"intensity"});
  } else if (kind == "spot") {
    allowed.insert(allowed.end(), {"intensity", "direction", "cone", "falloff"});
  } else if (kind == "directional") {
    allowed.insert(allowed.end(), {"irradiance", "direction"});
  } else if (kind == "sphere") {
    allowed.insert(allowed.end(), {"intensity", "radius"});
  } else {
    fail(type, fmt::format("unknown light type \"{}\" (expected one of: point, spot, "
                           "directional, sphere)",
                           kind));
  }
  object(n, allowed, {}, fmt::format(" for a {} light", kind));

  Light l;
  const Node name = member(n, "name");
  l.name = string(name);
  if (l.name.empty()) fail(name, "must not be empty");
  if (Node p = member(n, "position"); p.value) l.world_line.position = vec3(p);
  if (Node t = member(n, "time"); t.value) l.world_line.time = time(t);
  if (Node vel = member(n, "velocity"); vel.value) l.world_line.velocity = velocity(vel);
  if (Node m = member(n, "motion"); m.value) {
    if (kind == "directional")
      fail(m, "a directional light is at infinity: it has a velocity but no motion");
    if (hole_) refuse_near_hole(m, "motion (phases or keyframes) of a light");
    l.motion = body_motion(n, m, l.world_line);
  }
  // A directional light is at infinity, where its velocity is its speed.
  if (hole_ && kind != "directional") check_line_near_hole(n, l.world_line, "light");

  const Node color_node = member(n, "color"), blackbody = member(n, "blackbody");
  if (color_node.value && blackbody.value)
    fail(n, "must have at most one of: color, blackbody (found color, blackbody)");
  if (color_node.value) l.spectrum.emission = color(color_node);
  if (blackbody.value) {
    object(blackbody, {"temperature"});
    Blackbody b;
    b.temperature_k = positive(member(blackbody, "temperature"));
    l.spectrum.emission = b;
  }
  if (Node i = member(n, "intensity"); i.value) l.intensity = non_negative(i);

  if (kind == "point") {
    l.kind = PointLight{};
  } else if (kind == "spot") {
    SpotLight s;
    if (Node d = member(n, "direction"); d.value) s.direction = direction(d);
    if (Node cone = member(n, "cone"); cone.value) {
      s.cone_degrees = number(cone);
      if (!(s.cone_degrees > 0 && s.cone_degrees < 180))
        fail(cone, fmt::format("must be between 0 and 180 degrees (both excluded), got {}",
                               s.cone_degrees));
    }
    // The default soft edge, 5 degrees, shrinks to fit a cone narrower than 10 degrees.
    s.falloff_degrees = std::min(s.falloff_degrees, s.cone_degrees / 2);
    if (Node f = member(n, "falloff"); f.value) {
      s.falloff_degrees = number(f);
      if (!(s.falloff_degrees >= 0 && s.falloff_degrees <= s.cone_degrees / 2))
        fail(f, fmt::format("must be from 0 to half the cone ({} degrees), got {}",
                            s.cone_degrees / 2, s.falloff_degrees));
    }
    l.kind = s;
  } else if (kind == "directional") {
    DirectionalLight d;
    if (Node dir = member(n, "direction"); dir.value) d.direction = direction(dir);
    if (Node e = member(n, "irradiance"); e.value) d.irradiance = non_negative(e);
    l.kind = d;
  } else {
    l.kind = SphereLight{positive(member(n, "radius"))};
  }
  return l;
}

EmissionSpectrum SceneReader::emission_spectrum(const Node& n) const {
  object(n, {"wavelengths", "values"});
  const Node wavelengths = member(n, "wavelengths"), values = member(n, "values");
  auto list = [&](const Node& list_node) {
    const json& v = need(list_node);
    if (!v.is_array() || v.size() < 2)
      fail(list_node, fmt::format("must be an array of at least 2 numbers, got {}", describe(v)));
    std::vector<double> out;
    for (std::size_t i = 0; i < v.size(); ++i) out.push_back(number(element(list_node, i)));
    return out;
  };
  EmissionSpectrum s{list(wavelengths), list(values)};
  if (s.values.size() != s.wavelengths_nm.size())
    fail(values, fmt::format("must have as many entries as wavelengths ({}), got {}",
                             s.wavelengths_nm.size(), s.values.size()));
  for (std::size_t i = 0; i < s.wavelengths_nm.size(); ++i) {
    if (!(s.wavelengths_nm[i] > 0))
      fail(element(wavelengths, i),
           fmt::format("wavelengths must be greater than 0 nm, got {}", s.wavelengths_nm[i]));
    if (i > 0 && !(s.wavelengths_nm[i] > s.wavelengths_nm[i - 1]))
      fail(element(wavelengths, i),
           fmt::format("wavelengths must be strictly increasing ({} after {})", s.wavelengths_nm[i],
                       s.wavelengths_nm[i - 1]));
    if (s.values[i] < 0) fail(element(values, i), fmt::format("must be >= 0, got {}", s.values[i]));
  }
  return s;
}

Sky SceneReader::sky(const Node& n) {
  Sky s;
  if (Node stars = member(n, "stars"); stars.value) s.stars = sky_stars(stars);
  // The pattern: one of these, or none under stars alone (a black sky).
  const bool needs_pattern = !s.stars || n.value->contains("color") || n.value->contains("image") ||
                             n.value->contains("grid");
  if (!needs_pattern) {
    object(n, {"stars"}, {"velocity", "rotation"});
  } else {
    pattern(n, s);
  }
  if (Node v = member(n, "velocity"); v.value) s.velocity = velocity(v);
  if (Node r = member(n, "rotation"); r.value) s.rotation = rotation(r);
  return s;
}

std::optional<SkyStars> SceneReader::sky_stars(const Node& n) {
  SkyStars stars;
  if (n.value->is_boolean()) {
    if (!boolean(n)) return std::nullopt;
  } else {
    object(n, {}, {"catalogue", "magnitude_limit", "exposure"});
    if (Node c = member(n, "catalogue"); c.value) {
      stars.catalogue = string(c);
      if (stars.catalogue != "bright")
        fail(c, fmt::format("unknown catalogue '{}' (the one lightcone has: \"bright\", the "
                            "naked-eye stars)",
                            stars.catalogue));
    }
    if (Node m = member(n, "magnitude_limit"); m.value) stars.magnitude_limit = number(m);
    if (Node e = member(n, "exposure"); e.value) stars.exposure = number(e);
  }
  assets_.push_back({Asset::kStars, 0, bright_star_catalogue_path(), n.path()});
  return stars;
}

void SceneReader::pattern(const Node& n, Sky& s) {
  const std::string_view kind =
      one_of(n, {"color", "image", "grid"}, {"velocity", "rotation", "stars"});
  const Node body = member(n, kind);
  if (kind == "color") {
    s.pattern = SolidColor{color(body)};
  } else if (kind == "image") {
    assets_.push_back({Asset::kSkyImage, 0, file_path(body), body.path()});
    s.pattern = SkyImage{};
  } else {
    object(body, {"spacing", "line_width", "color", "background"});
    SkyGrid grid;
    if (Node spacing = member(body, "spacing"); spacing.value) {
      grid.spacing_degrees = number(spacing);
      if (!(grid.spacing_degrees > 0 && grid.spacing_degrees <= 90))
        fail(spacing, fmt::format("must be greater than 0 and at most 90 degrees, got {}",
                                  grid.spacing_degrees));
    }
    if (Node w = member(body, "line_width"); w.value) grid.line_width_degrees = positive(w);
    if (Node c = member(body, "color"); c.value) grid.line_color = color(c);
    if (Node b = member(body, "background"); b.value) grid.background = color(b);
    s.pattern = grid;
  }
}

}  // namespace lightcone::scene_io
