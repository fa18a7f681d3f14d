#include "lightcone/frame/lighting.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "lightcone/color/colour_models.hpp"
#include "lightcone/frame/received_colour.hpp"
#include "lightcone/frame/shading.hpp"
#include "lightcone/physics/doppler.hpp"
#include "lightcone/physics/emission_root.hpp"
#include "lightcone/physics/hole_light_leg.hpp"
#include "lightcone/physics/light_path.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/physics/retarded_time.hpp"
#include "lightcone/portable.hpp"

namespace lightcone {
namespace {

constexpr double kPi = std::numbers::pi;
// Shadow segments start and end this fraction of their length away from their events, so
// that the lit surface and the light's own sphere do not shadow themselves.
constexpr double kShadowEpsilon = 1e-5;

// Uniform point on the unit sphere from two numbers in [0, 1).
Vec3 sphere_point(const std::array<double, 2>& u) {
  const double z = 1 - 2 * u[0], r = std::sqrt(std::max(0.0, 1 - z * z)), phi = 2 * kPi * u[1];
  return {r * std::cos(phi), r * std::sin(phi), z};
}

double smoothstep(double e0, double e1, double x) {
  if (e1 <= e0) return x >= e1 ? 1.0 : 0.0;
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

// The reflectance of the glossy layer (spectrally flat): GGX normal distribution, Smith's
// exact masking for GGX, Schlick's Fresnel. Directions unit, in the surface's rest frame.
double glossy_reflectance(const Glossy& g, const Vec3& n, const Vec3& to_light,
                          const Vec3& to_camera) {
  const double cos_i = dot(n, to_light), cos_o = dot(n, to_camera);
  if (cos_i <= 0 || cos_o <= 0) return 0;
  const Vec3 h = normalize(to_light + to_camera);
  const double a2 = std::pow(g.roughness, 4);  // alpha = roughness^2
  const double cos_h = dot(n, h);
  const double denom = cos_h * cos_h * (a2 - 1) + 1;
  const double distribution = a2 / (kPi * denom * denom);
  auto g1 = [&](double c) { return 2 * c / (c + std::sqrt(a2 + (1 - a2) * c * c)); };
  const double fresnel = g.specular + (1 - g.specular) * std::pow(1 - dot(h, to_camera), 5);
  return distribution * g1(cos_i) * g1(cos_o) * fresnel / (4 * cos_i * cos_o);
}

// The irradiance factors of `in` under the searchlight model: the light-path kernels' laws
// (physical), or the geometric irradiance times D (Chang et al. 1996) or times 1 (off).
template <class Incoming>
void set_irradiance(Incoming& in, SearchlightModel model, double geometric, double physical,
                    double physical_spectral) {
  switch (model) {
    case SearchlightModel::kPhysical:
      in.irradiance = physical;
      in.spectral_factor = physical_spectral;
      return;
    case SearchlightModel::kChang1996:
      in.irradiance = in.spectral_factor = geometric * in.doppler;
      return;
    case SearchlightModel::kOff:
      break;
  }
  in.irradiance = in.spectral_factor = geometric;
}

// A light's emission event where it does not depend on the lit point (ResolvedLight's
// fixed_event): on the camera's past light cone ("camera" delay), or where it is at the
// observation time ("none", and the classical picture); none near a hole or for the exact delay.
std::optional<Vec4> fixed_emission(const ResolvedScene& scene, const Light& light) {
  const RenderSettings& settings = scene.scene->render;
  const WorldLine& line = light.world_line;
  const Vec4& observation = scene.observation_event;
  if (scene.hole) return std::nullopt;
  if (settings.relativity && settings.light_source_delay == LightSourceDelay::kCamera) {
    const Vec3 at_observation = line.position_at(observation.t);
    const double tau = retarded_delay(at_observation - observation.x, line.velocity);
    return Vec4{observation.t - tau, at_observation - line.velocity * tau};
  }
  if (lit_from_retarded_event(settings)) return std::nullopt;
  // Where the light is at the observation time: in the classical picture too, as its bodies are
  // drawn where they are then (its light there carries no Doppler factor or aberration).
  return Vec4{observation.t, line.position_at(observation.t)};
}

}  // namespace

double Lighting::ResolvedLight::spectral(double lambda_nm) const {
  if (const auto* s = std::get_if<RgbEmitterSpectrum>(&spectrum)) return (*s)(lambda_nm);
  return std::get<BlackbodySpectrum>(spectrum)(lambda_nm);
}

Lighting::Lighting(const ResolvedScene& scene, const ShadowQuery* shadows,
                   const CurvedShadowQuery* curved_shadows, double margin)
    : scene_(&scene), shadows_(shadows), curved_shadows_(curved_shadows) {
  const Scene& s = *scene.scene;
  const RenderSettings& settings = s.render;
  settings_ = settings;
  unshifted_ = settings;
  unshifted_.searchlight = SearchlightModel::kOff;
  for (const Light& light : s.lights) {
    ResolvedLight r;
    r.light = &light;
    if (const auto* rgb = std::get_if<Rgb>(&light.spectrum.emission)) {
      r.rgb = {rgb->r, rgb->g, rgb->b};
      r.spectrum = RgbEmitterSpectrum::from_rgb(r.rgb);
    } else {
      const auto b = BlackbodySpectrum::with_luminance(
          std::get<Blackbody>(light.spectrum.emission).temperature_k, 1.0);
      r.rgb = linear_srgb_from_xyz(xyz_from_spectrum(b));
      r.spectrum = b;
    }
    const WorldLine& line = light.world_line;
    if (scene.hole && !std::holds_alternative<DirectionalLight>(light.kind))
      // Always the exact delay, along the curved ray.
      r.near_hole = hole_world_line(*scene.hole, line);
    r.fixed_event = fixed_emission(scene, light);
    lights_.push_back(std::move(r));
  }
  // The factors a lit surface can see a light with (any direction); near a hole, with the
  // gravitational shift between their depths in its well.
  if (scene.hole) {
    for (const ResolvedBody& body : scene.bodies) {
      if (body.object->material.unlit) continue;
      const HoleDepth surface = object_depth(*scene.hole, *body.object);
      for (const Light& light : s.lights) {
        const HoleDepth lamp = light_depth(*scene.hole, light);
        const double speeds = surface.rapidity + lamp.rapidity;
        light_rapidity_ =
            std::max({light_rapidity_, speeds - lamp.log_lapse, speeds - surface.log_lapse});
      }
    }
  } else if (settings.relativity)
    for (const ResolvedBody& body : scene.bodies) {
      if (body.object->material.unlit) continue;
      const double spin = body.spin >= 0 ? spin_rapidity(scene.spins[body.spin]) : 0.0;
      for (const Light& light : s.lights)
        light_rapidity_ = std::max(
            light_rapidity_,
            relative_rapidity(light.world_line.velocity, body.object->world_line.velocity) + spin);
    }
  if (settings.doppler != DopplerModel::kSpectral) return;

  const double light_reach = light_rapidity_;
  seen_ = visible_log_doppler(scene, true);
  seen_.lo -= margin;
  seen_.hi += margin;
  // The lights' spectra are 0 at and below the shortest of their zero wavelengths, and the
  // albedos constant below kCieMinWavelength: the lights' own tables, read at d_camera d_light,
  // are constant where that product is below the first divided by kCieMaxWavelength, the
  // reflections (their light at d_camera d_light lambda) where d_camera is below that over the
  // light grid's largest factor.
  double constant_below = kCieMinWavelength;
  for (const ResolvedLight& r : lights_)
    constant_below = std::min(
        constant_below, std::visit([](const auto& s) { return s.constant_below(); }, r.spectrum));
  light_grid_ = DopplerGrid::covering(light_reach);
  camera_grid_ = DopplerGrid::reaching(seen_.lo, seen_.hi,
                                       constant_below / light_grid_.d(light_grid_.size() - 1));
  const DopplerGrid total =
      DopplerGrid::reaching(seen_.lo - light_reach, seen_.hi + light_reach, constant_below);
  for (ResolvedLight& r : lights_)
    r.seen = DopplerXyzTable::of([&r](double l) { return r.spectral(l); }, total);

  // One table per distinct (albedo, light, kind): objects of one colour share them. A light
  // at rest relative to the body (D = 1 on its leg, whatever the direction) needs only the
  // camera's factor: a table in one variable, cheaper to build and to read.
  struct Key {
    float r, g, b;
    std::size_t light;
    bool co_moving;
  };
  std::vector<std::pair<Key, Reflection>> made;
  const auto table_for = [&](const Rgb& albedo, std::size_t l, bool co_moving) {
    for (const auto& [key, table] : made)
      if (key.r == albedo.r && key.g == albedo.g && key.b == albedo.b && key.light == l &&
          key.co_moving == co_moving)
        return table;
    const RgbAlbedoSpectrum rho = RgbAlbedoSpectrum::from_rgb({albedo.r, albedo.g, albedo.b});
    const ResolvedLight& light = lights_[l];
    Reflection t;
    if (co_moving)
      t.co_moving = &co_moving_reflections_.emplace_back(DopplerXyzTable::of(
          [&](double lambda) { return rho(lambda) * light.spectral(lambda); }, camera_grid_));
    else
      t.moving = &reflections_.emplace_back(ReflectionXyzTable::of(
          rho, [&light](double lambda) { return light.spectral(lambda); }, camera_grid_,
          light_grid_, ParallelNodes{}));
    made.push_back({{albedo.r, albedo.g, albedo.b, l, co_moving}, t});
    return t;
  };
  if (lights_.empty()) return;  // nothing is lit: no object's row is read
  object_reflections_.resize(s.objects.size());
  for (std::size_t o = 0; o < s.objects.size(); ++o) {
    const Material& m = s.objects[o].material;
    if (m.unlit) continue;
    Rgb colours[2];
    const int count = pattern_colours(m, colours);
    for (std::size_t l = 0; l < lights_.size(); ++l) {
      // (A spinning body's points move relative to its centre.)
      const bool co_moving =
          !settings.relativity ||
          (!scene.hole &&
           (scene.bodies[o].spin < 0 && relative_rapidity(lights_[l].light->world_line.velocity,
                                                          s.objects[o].world_line.velocity) == 0));
      for (int k = 0; k < count; ++k)
        object_reflections_[o][k].push_back(table_for(colours[k], l, co_moving));
    }
  }
}

ShadowRay Lighting::shadow_ray(const ResolvedLight& rl, const Vec4& surface_world,
                               const Vec4& direction, double t_far, const Vec4& light_end) const {
  const auto l = static_cast<std::size_t>(&rl - lights_.data());
  const ShadowLight& shadow = scene_->shadow_lights[l];
  return {surface_world, direction,           kShadowEpsilon,
          t_far,         static_cast<int>(l), shadow.label(light_end)};
}

bool Lighting::incoming(const ResolvedLight& rl, const Vec4& surface_world,
                        const Vec3& surface_velocity, const Vec3& normal,
                        const std::array<double, 2>& light_sample, Incoming& out,
                        std::optional<ShadowRay>& shadow) const {
  shadow.reset();
  const Light& light = *rl.light;
  const RenderSettings& settings = scene_->scene->render;
  const Vec3 light_velocity = settings.relativity ? light.world_line.velocity : Vec3{};

  if (const auto* sun = std::get_if<DirectionalLight>(&light.kind)) {
    // A plane wave: its propagation direction and frequency carried into the surface's frame.
    const Vec4 k_light{1.0, normalize(sun->direction)};
    const Vec4 k_world = boost(-light_velocity) * k_light;
    const Vec4 k_surface = boost(surface_velocity) * k_world;
    out.direction_to_light = -(k_surface.x / k_surface.t);
    out.doppler = k_surface.t / k_light.t;
    const double cos_i = dot(normal, out.direction_to_light);
    if (!(cos_i > 0)) return false;
    set_irradiance(out, settings.searchlight, sun->irradiance * cos_i,
                   plane_wave_irradiance(out.doppler, sun->irradiance, cos_i),
                   sun->irradiance * plane_wave_spectral_factor(out.doppler, cos_i));
    if (settings.shadows && shadows_) {
      // Backward along the light's direction, as far as shadow rays are bounded.
      const Vec4 back = (-1.0 / k_world.t) * k_world;
      const double reach = surface_world.t - scene_->shadow_time_min;
      if (reach > 0) shadow = shadow_ray(rl, surface_world, back, reach, surface_world);
    }
    return true;
  }

  // The emitting point in the light's rest frame: its centre, or a point of a sphere light.
  Vec3 rest_offset;
  double intensity = light.intensity;
  const auto* sphere = std::get_if<SphereLight>(&light.kind);
  if (sphere) rest_offset = sphere_point(light_sample) * sphere->radius;

  // Its emission event, by the light-source delay mode.
  const Vec3 offset_world = contracted_offset(rest_offset, light_velocity);
  auto position = [&](double t) {
    return light.world_line.position + light_velocity * (t - light.world_line.time) + offset_world;
  };
  Vec4 emission;
  if (rl.fixed_event) {
    emission = *rl.fixed_event;
    emission.x += offset_world;
  } else {
    const Vec3 at = position(surface_world.t);
    const double tau = retarded_delay(at - surface_world.x, light_velocity);
    emission = {surface_world.t - tau, at - light_velocity * tau};
  }

  const ReceivedLeg leg = receive_leg(emission, light_velocity, surface_world, surface_velocity);
  out.direction_to_light = -leg.direction;
  out.doppler = leg.doppler;
  const double cos_i = dot(normal, out.direction_to_light);
  // A light at the surface point itself (zero distance) has no direction: it lights nothing.
  if (!(cos_i > 0) || !(leg.distance > 0)) return false;

  if (const auto* spot = std::get_if<SpotLight>(&light.kind)) {
    const double angle =
        std::acos(std::clamp(dot(leg.emitted_direction, normalize(spot->direction)), -1.0, 1.0)) *
        180 / kPi;
    const double half = spot->cone_degrees / 2;
    intensity *= 1 - smoothstep(half - spot->falloff_degrees, half, angle);
  } else if (sphere) {
    // One area sample of a sphere of uniform radiance I / (pi R^2): the estimator of its
    // intensity toward the surface is 4 I cos(theta) on the visible side.
    intensity *= 4 * std::max(0.0, dot(normalize(rest_offset), leg.emitted_direction));
  }
  if (intensity <= 0) return false;
  set_irradiance(out, settings.searchlight, intensity * cos_i / (leg.distance * leg.distance),
                 point_source_irradiance(leg, intensity, cos_i),
                 intensity * point_source_spectral_factor(leg, cos_i));

  if (settings.shadows && shadows_)
    shadow = shadow_ray(rl, surface_world, emission - surface_world, 1 - kShadowEpsilon, emission);
  return true;
}

bool Lighting::incoming_near_hole(const ResolvedLight& rl, const Vec4& surface_world,
                                  const Vec3& surface_velocity, const Vec3& normal,
                                  const std::array<double, 2>& light_sample, int order,
                                  Incoming& out, std::optional<CurvedShadowRay>& shadow,
                                  RayBetweenStart* warm_start) const {
  shadow.reset();
  const Light& light = *rl.light;
  const RenderSettings& settings = scene_->scene->render;
  // The legs are solved in units of the hole's mass (hole_view.hpp); their distance is W's.
  const HoleView& hole = *scene_->hole;
  const Vec4 surface = in_hole_units(hole, surface_world);
  const Vec3& receiver = surface.x;
  // The path from the surface to the light, which is at radius `light_radius` (in units of M;
  // infinity for a plane wave), less kShadowEpsilon of it at either end.
  const auto shadow_along = [&](const HoleLegPath& path, double near, double far,
                                double light_radius) {
    if (!settings.shadows || !curved_shadows_) return;
    const double r = length(receiver), span = light_radius - r;
    const bool finite = std::isfinite(light_radius);
    shadow = CurvedShadowRay{surface_world,
                             path.e1,
                             path.e2,
                             path.impact,
                             path.outward,
                             near,
                             far,
                             finite ? r + kShadowEpsilon * span : r * (1 + kShadowEpsilon),
                             finite ? light_radius - kShadowEpsilon * span : light_radius};
  };

  if (const auto* sun = std::get_if<DirectionalLight>(&light.kind)) {
    // A plane wave far away, its frequency there carried from the light's frame into W; the
    // hole bends, focuses and blueshifts it on the way in.
    const Vec4 k_light{1.0, normalize(sun->direction)};
    const Vec4 k_world = boost(-light.world_line.velocity) * k_light;
    const auto wave = hole_plane_wave(hole.mass, receiver, surface_velocity, k_world.x / k_world.t,
                                      order, warm_start, &normal);
    if (!wave) return false;
    out.direction_to_light = -wave->direction;
    out.doppler = wave->doppler * k_world.t / k_light.t;
    const double cos_i = dot(normal, out.direction_to_light);
    if (!(cos_i > 0)) return false;
    const double irradiance = sun->irradiance * wave->focusing;
    set_irradiance(out, settings.searchlight, irradiance * cos_i,
                   plane_wave_irradiance(out.doppler, irradiance, cos_i),
                   irradiance * plane_wave_spectral_factor(out.doppler, cos_i));
    shadow_along(wave->path, kShadowEpsilon * wave->path.sweep, wave->path.sweep,
                 std::numeric_limits<double>::infinity());
    return true;
  }

  // The emitting point: the centre, or a point of a sphere light (its offset contracted by its
  // coordinate velocity, as bodies' shapes are), on the light's coordinate line.
  const HoleWorldLine& line = *rl.near_hole;
  Vec3 rest_offset;
  double intensity = light.intensity;
  const auto* sphere = std::get_if<SphereLight>(&light.kind);
  if (sphere) rest_offset = sphere_point(light_sample) * sphere->radius;
  const Vec3 offset = contracted_offset(rest_offset, light.world_line.velocity) / hole.scale;
  // The light that reaches the surface event left at t_e with t_s - t_e the coordinate time of
  // the direct ray from where the light then was: exact for a light at rest; on a moving line
  // the root of that equation (physics/emission_root.hpp).
  // A light at rest lights only the side it faces (one on a line may face it from where it was),
  // and from where it always is: its leg's time is not needed.
  HoleWorldLineState state = line.at(surface.t);
  const bool still = line.still();
  auto leg = hole_light_leg(hole.mass, state.position + offset, state.local_velocity, receiver,
                            surface_velocity, order, warm_start, still ? &normal : nullptr, !still);
  if (!leg) return false;
  if (!still) {
    const auto leg_at = [&](double t) {
      state = line.at(t);
      return hole_light_leg(hole.mass, state.position + offset, state.local_velocity, receiver,
                            surface_velocity, order, warm_start);
    };
    const auto late = [&](double t) {
      const auto l = leg_at(t);
      return l ? t + l->time - surface.t : std::numeric_limits<double>::quiet_NaN();
    };
    const auto root = emission_time_root(late, surface.t, surface.t, leg->time);
    if (!root) return false;
    const double t_e = *root;
    leg = leg_at(t_e);
    if (!leg) return false;
  }
  leg->leg.distance *= hole.scale;
  out.direction_to_light = -leg->leg.direction;
  out.doppler = leg->leg.doppler;
  const double cos_i = dot(normal, out.direction_to_light);
  if (!(cos_i > 0)) return false;
  if (const auto* spot = std::get_if<SpotLight>(&light.kind)) {
    const double angle =
        std::acos(
            std::clamp(dot(leg->leg.emitted_direction, normalize(spot->direction)), -1.0, 1.0)) *
        180 / kPi;
    const double half = spot->cone_degrees / 2;
    intensity *= 1 - smoothstep(half - spot->falloff_degrees, half, angle);
  } else if (sphere) {
    intensity *= 4 * std::max(0.0, dot(normalize(rest_offset), leg->leg.emitted_direction));
  }
  if (intensity <= 0) return false;
  const double distance = leg->leg.distance;
  set_irradiance(out, settings.searchlight, intensity * cos_i / (distance * distance),
                 point_source_irradiance(leg->leg, intensity, cos_i),
                 intensity * point_source_spectral_factor(leg->leg, cos_i));
  shadow_along(leg->path, kShadowEpsilon * leg->path.sweep, (1 - kShadowEpsilon) * leg->path.sweep,
               length(state.position + offset));
  return true;
}

Xyz Lighting::reflected_at(const Reflection& t, const GridStencil& camera, double d_camera,
                           double d_light) {
  // A co-moving light's leg has D = 1 (to rounding), so only the camera's factor counts.
  if (t.co_moving) return d_camera == 1 ? t.co_moving->at_rest() : (*t.co_moving)(camera.position);
  if (d_camera == 1 && d_light == 1) return t.moving->at_rest();
  return (*t.moving)(camera, d_light);
}

Xyz Lighting::reflected(std::size_t object, int colour, std::size_t l, double d_camera,
                        double d_light) const {
  return reflected_at(object_reflections_[object][static_cast<std::size_t>(colour)][l],
                      grid_stencil(camera_grid_, d_camera), d_camera, d_light);
}

struct Lighting::Shading {
  const Material* material = nullptr;
  const LinearRgb* albedo = nullptr;
  Vec4 surface_world;                        // the surface event
  Vec3 surface_velocity, normal, to_camera;  // W; rest-frame unit normal and direction to camera
  bool near_hole = false;  // (then surface_velocity is against the static observer there)
  double d_camera = 1;
  double diffuse = 1;  // the diffuse layer's share
  // Spectral: the colour reaching the camera before its searchlight factor, and the tables it
  // is read from (the fixed colour's, or else a spectrum fitted to the albedo per hit).
  // Otherwise: the surface-frame outgoing radiance, shifted to the camera afterwards.
  Xyz seen;
  LinearRgb outgoing{0, 0, 0};
  GridStencil camera_stencil;
  const std::vector<Reflection>* reflections = nullptr;
  RgbAlbedoSpectrum per_hit_albedo;
};

void Lighting::prepare(const LitPoint& point, Shading& shading) const {
  const RenderSettings& settings = scene_->scene->render;
  const Hit& hit = *point.hit;
  const Object& object = *scene_->bodies[hit.body].object;
  shading.material = &object.material;
  shading.albedo = &point.surface.rest_rgb;
  shading.d_camera = point.d_camera;

  // The surface event and velocity, and its rest-frame normal and direction to the camera.
  const ResolvedBody& body = scene_->bodies[hit.body];
  shading.normal = normalize(object.rotation * component_div(hit.shape_normal, object.scale));
  if (point.near_hole) {
    // Against the static observer at the event (bodies near a hole do not spin).
    shading.near_hole = true;
    shading.surface_world = point.near_hole->event;
    shading.surface_velocity = point.near_hole->local_velocity;
    const Vec4 k = boost(shading.surface_velocity) * Vec4{1, point.near_hole->to_camera};
    shading.to_camera = k.x / k.t;
  } else {
    const Vec4 surface_trace{scene_->ray_time * hit.s, point.u * hit.s};
    shading.surface_world = scene_->trace_to_world(surface_trace);
    // A spinning body's point moves and is turned with its spin; the normal is taken in the
    // body's rest frame (docs/design/spinning-bodies.md).
    shading.surface_velocity =
        !settings.relativity ? Vec3{}
        : body.spin >= 0     ? velocity_of(scene_->trace_to_world.linear * Vec4{1, hit.velocity})
                             : object.world_line.velocity;
    if (body.spin >= 0)
      shading.normal =
          Mat3::rotation(scene_->spins[body.spin].axis, hit.spin_angle) * shading.normal;
    const Vec3 camera_velocity =
        settings.relativity ? scene_->scene->camera.world_line.velocity : Vec3{};
    shading.to_camera = receive_leg(shading.surface_world, shading.surface_velocity,
                                    scene_->observation_event, camera_velocity)
                            .emitted_direction;
  }
  shading.diffuse = object.material.glossy ? 1 - object.material.glossy->specular : 1.0;
  if (settings.doppler != DopplerModel::kSpectral) return;
  if (lights_.empty()) return;  // nothing to reflect (and no rows kept: the constructor)
  shading.camera_stencil = grid_stencil(camera_grid_, point.d_camera);
  if (point.surface.fixed_colour >= 0)
    shading.reflections =
        &object_reflections_[hit.body][static_cast<std::size_t>(point.surface.fixed_colour)];
  else
    shading.per_hit_albedo = RgbAlbedoSpectrum::from_rgb(point.surface.rest_rgb);
}

void Lighting::add_light(std::size_t l, const Incoming& in, Shading& shading) const {
  const RenderSettings& settings = scene_->scene->render;
  const ResolvedLight& light = lights_[l];
  const Material& material = *shading.material;
  const double d_camera = shading.d_camera;
  const double gloss = material.glossy
                           ? glossy_reflectance(*material.glossy, shading.normal,
                                                in.direction_to_light, shading.to_camera)
                           : 0.0;
  if (settings.doppler == DopplerModel::kSpectral) {
    // Reflected per unit spectral irradiance: albedo / pi (diffuse) plus the flat glossy lobe.
    const bool at_rest = d_camera == 1 && in.doppler == 1;
    Xyz reflected;
    if (shading.reflections)
      reflected =
          reflected_at((*shading.reflections)[l], shading.camera_stencil, d_camera, in.doppler);
    else
      reflected = xyz_of_reflection_seen_with_doppler(
          shading.per_hit_albedo, [&light](double lambda) { return light.spectral(lambda); },
          d_camera, in.doppler);
    const double kd = shading.diffuse / kPi * in.spectral_factor;
    shading.seen.x += kd * reflected.x;
    shading.seen.y += kd * reflected.y;
    shading.seen.z += kd * reflected.z;
    if (gloss > 0) {
      const Xyz direct = at_rest ? light.seen.at_rest() : light.seen(d_camera * in.doppler);
      const double ks = gloss * in.spectral_factor;
      shading.seen.x += ks * direct.x;
      shading.seen.y += ks * direct.y;
      shading.seen.z += ks * direct.z;
    }
    return;
  }
  // The light's colour as the surface sees it, under the chosen model (its irradiance apart),
  // then reflected.
  const LinearRgb colour = received_colour(PointEmission{light.rgb}, in.doppler, unshifted_);
  const LinearRgb& albedo = *shading.albedo;
  auto brdf = [&](double albedo_value) { return shading.diffuse * albedo_value / kPi + gloss; };
  shading.outgoing.r += brdf(albedo.r) * colour.r * in.irradiance;
  shading.outgoing.g += brdf(albedo.g) * colour.g * in.irradiance;
  shading.outgoing.b += brdf(albedo.b) * colour.b * in.irradiance;
}

LinearRgb Lighting::finish(const Shading& shading) const {
  const double d_camera = shading.d_camera;
  const RenderSettings& settings = scene_->scene->render;
  if (settings.doppler == DopplerModel::kSpectral) {
    const LinearRgb c = linear_srgb_from_xyz(shading.seen);
    const double k = spectral_searchlight(d_camera, settings.searchlight);
    return {c.r * k, c.g * k, c.b * k};
  }
  return received_colour(PointEmission{shading.outgoing}, d_camera, settings);
}

bool Lighting::serves(const ResolvedScene& next) const {
  const RenderSettings& n = next.scene->render;
  if (next.scene != scene_->scene || next.hole || n.relativity != settings_.relativity ||
      n.doppler != settings_.doppler || n.searchlight != settings_.searchlight ||
      n.light_source_delay != settings_.light_source_delay || n.shadows != settings_.shadows ||
      next.scene->lights.size() != lights_.size())
    return false;
  for (const ResolvedLight& light : lights_) {
    const std::optional<Vec4> fixed = fixed_emission(next, *light.light);
    if (fixed.has_value() != light.fixed_event.has_value()) return false;
    if (fixed && (fixed->t != light.fixed_event->t || fixed->x.x != light.fixed_event->x.x ||
                  fixed->x.y != light.fixed_event->x.y || fixed->x.z != light.fixed_event->x.z))
      return false;
  }
  if (n.doppler != DopplerModel::kSpectral) return true;
  const LogDopplerRange r = visible_log_doppler(next, true);
  return seen_.lo <= r.lo && r.hi <= seen_.hi;
}

LinearRgb Lighting::received(const Hit& hit, const Vec3& u, double d_camera,
                             const PointEmission& surface,
                             const std::array<double, 2>& light_sample) const {
  const LitPoint point{&hit, u, d_camera, surface, light_sample};
  LinearRgb out;
  received(std::span(&point, 1), std::span(&out, 1));
  return out;
}

void Lighting::received(std::span<const LitPoint> points, std::span<LinearRgb> out) const {
  for (std::size_t first = 0; first < points.size(); first += kBatchSize) {
    const std::size_t count = std::min(kBatchSize, points.size() - first);
    Shading shading[kBatchSize];
    for (std::size_t p = 0; p < count; ++p) prepare(points[first + p], shading[p]);
    for (std::size_t l = 0; l < lights_.size(); ++l) {
      // What light l delivers to each point, and the shadow rays that decide whether it does.
      Incoming in[kBatchSize];
      bool arrives[kBatchSize];
      ShadowRay rays[kBatchSize];
      bool blocked[kBatchSize];
      std::size_t ray_point[kBatchSize], ray_count = 0;
      // Near a hole: each leg's light at the last point, which the next reuses where it is the
      // same surface point (a raster vertex asks once per fixed colour of its material).
      Incoming legs[2];
      bool leg_arrives[2] = {false, false};
      for (std::size_t p = 0; p < count; ++p) {
        if (shading[p].near_hole) {
          const LitPoint &point = points[first + p],
                         *last = p > 0 ? &points[first + p - 1] : nullptr;
          const bool same_surface = last && last->near_hole == point.near_hole &&
                                    last->hit == point.hit &&
                                    last->light_sample == point.light_sample;
          // Directly and round the far side (the higher orders bring a few thousandths of it).
          arrives[p] = false;
          for (const int order : {0, 1}) {
            if (!same_surface) {
              std::optional<CurvedShadowRay> curved;
              HoleLegStarts* starts = point.near_hole->leg_starts;
              leg_arrives[order] =
                  incoming_near_hole(lights_[l], shading[p].surface_world,
                                     shading[p].surface_velocity, shading[p].normal,
                                     point.light_sample, order, legs[order], curved,
                                     starts ? &starts->at(point.hit->body, l, order) : nullptr) &&
                  !(curved && curved_shadows_->occluded(*curved));
            }
            if (leg_arrives[order]) add_light(l, legs[order], shading[p]);
          }
          continue;
        }
        std::optional<ShadowRay> shadow;
        arrives[p] = incoming(lights_[l], shading[p].surface_world, shading[p].surface_velocity,
                              shading[p].normal, points[first + p].light_sample, in[p], shadow);
        if (arrives[p] && shadow) {
          rays[ray_count] = *shadow;
          ray_point[ray_count++] = p;
        }
      }
      if (ray_count > 0) {
        shadows_->occluded(std::span(rays, ray_count), std::span(blocked, ray_count));
        for (std::size_t r = 0; r < ray_count; ++r)
          if (blocked[r]) arrives[ray_point[r]] = false;
      }
      for (std::size_t p = 0; p < count; ++p)
        if (arrives[p]) add_light(l, in[p], shading[p]);
    }
    for (std::size_t p = 0; p < count; ++p) out[first + p] = finish(shading[p]);
  }
}

}  // namespace lightcone
