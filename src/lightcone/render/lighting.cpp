#include "lightcone/render/lighting.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "lightcone/color/colour_models.hpp"
#include "lightcone/physics/doppler.hpp"
#include "lightcone/physics/light_path.hpp"
#include "lightcone/physics/lorentz.hpp"
#include "lightcone/physics/retarded_time.hpp"
#include "lightcone/render/received_colour.hpp"

namespace lightcone {
namespace {

constexpr double kPi = std::numbers::pi;
// Shadow segments start and end this fraction of their length away from their events, so
// that the lit surface and the light's own sphere do not shadow themselves.
constexpr double kShadowEpsilon = 1e-5;

// Where the rest point `offset` of a body moving with beta is, relative to the body's origin,
// at one instant of W: contracted along beta.
Vec3 contracted(const Vec3& offset, const Vec3& beta) {
  const double b2 = dot(beta, beta);
  if (b2 == 0) return offset;
  const double g = lorentz_gamma(beta);
  return offset - beta * ((1 - 1 / g) * dot(beta, offset) / b2);
}

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

}  // namespace

double Lighting::ResolvedLight::spectral(double lambda_nm) const {
  if (const auto* s = std::get_if<RgbIlluminantSpectrum>(&spectrum)) return (*s)(lambda_nm);
  return std::get<BlackbodySpectrum>(spectrum)(lambda_nm);
}

Lighting::Lighting(const ResolvedScene& scene, const Tracer& tracer)
    : scene_(scene), tracer_(tracer) {
  const Vec4& observation = scene.observation_event;
  for (const Light& light : scene.scene->lights) {
    ResolvedLight r;
    r.light = &light;
    if (const auto* rgb = std::get_if<Rgb>(&light.spectrum.emission)) {
      r.rgb = {rgb->r, rgb->g, rgb->b};
      r.spectrum = RgbIlluminantSpectrum::from_rgb(r.rgb);
    } else {
      const auto b = BlackbodySpectrum::with_luminance(
          std::get<Blackbody>(light.spectrum.emission).temperature_k, 1.0);
      r.rgb = linear_srgb_from_xyz(xyz_from_spectrum(b));
      r.spectrum = b;
    }
    const WorldLine& line = light.world_line;
    const Vec3 at_observation = line.position_at(observation.t);
    const double tau = retarded_delay(at_observation - observation.x, line.velocity);
    r.camera_event = {observation.t - tau, at_observation - line.velocity * tau};
    lights_.push_back(r);
  }
}

bool Lighting::incoming(const ResolvedLight& rl, const Vec4& surface_world,
                        const Vec3& surface_velocity, const Vec3& normal,
                        const std::array<double, 2>& light_sample, Incoming& out) const {
  const Light& light = *rl.light;
  const RenderSettings& settings = scene_.scene->render;
  const Vec3 light_velocity = settings.relativity ? light.world_line.velocity : Vec3{};

  if (const auto* sun = std::get_if<DirectionalLight>(&light.kind)) {
    // A plane wave: its propagation direction and frequency carried into the surface's frame.
    const Vec4 k_light{1.0, normalize(sun->direction)};
    const Vec4 k_world = boost(-light_velocity) * k_light;
    const Vec4 k_surface = boost(surface_velocity) * k_world;
    out.direction_to_light = -(k_surface.x / k_surface.t);
    out.doppler = k_surface.t / k_light.t;
    out.doppler_power = 2;  // a plane wave's irradiance scales as D^2
    const double cos_i = dot(normal, out.direction_to_light);
    if (!(cos_i > 0)) return false;
    out.weight = sun->irradiance * cos_i;
    if (settings.shadows) {
      // Backward along the light's direction, as far as shadow rays are bounded.
      const Vec4 back = (-1.0 / k_world.t) * k_world;
      const double reach = surface_world.t - scene_.shadow_time_min;
      if (reach > 0 && tracer_.occluded(surface_world, back, kShadowEpsilon, reach)) return false;
    }
    return true;
  }

  // The emitting point in the light's rest frame: its centre, or a point of a sphere light.
  Vec3 rest_offset;
  double intensity = light.intensity;
  const auto* sphere = std::get_if<SphereLight>(&light.kind);
  if (sphere) rest_offset = sphere_point(light_sample) * sphere->radius;

  // Its emission event, by the light-source delay mode.
  const Vec3 offset_world = contracted(rest_offset, light_velocity);
  auto position = [&](double t) {
    return light.world_line.position + light_velocity * (t - light.world_line.time) + offset_world;
  };
  Vec4 emission;
  const bool exact =
      settings.relativity && settings.light_source_delay == LightSourceDelay::kSurface;
  if (exact) {
    const Vec3 at = position(surface_world.t);
    const double tau = retarded_delay(at - surface_world.x, light_velocity);
    emission = {surface_world.t - tau, at - light_velocity * tau};
  } else if (settings.relativity && settings.light_source_delay == LightSourceDelay::kCamera) {
    emission = rl.camera_event;
    emission.x += offset_world;
  } else {
    const double t = scene_.observation_event.t;
    emission = {t, position(t)};
  }

  const ReceivedLeg leg = receive_leg(emission, light_velocity, surface_world, surface_velocity);
  out.direction_to_light = -leg.direction;
  out.doppler = leg.doppler;
  out.doppler_power = 4;
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
  out.weight = intensity * cos_i / (leg.distance * leg.distance);

  if (settings.shadows &&
      tracer_.occluded(surface_world, emission - surface_world, kShadowEpsilon, 1 - kShadowEpsilon))
    return false;
  return true;
}

LinearRgb Lighting::received(const Hit& hit, const Vec3& u, double d_camera,
                             const LinearRgb& albedo, const SampledWavelengths& wavelengths,
                             const std::array<double, 2>& light_sample) const {
  const RenderSettings& settings = scene_.scene->render;
  const Object& object = *scene_.bodies[hit.body].object;
  const Material& material = object.material;

  // The surface event and velocity, and its rest-frame normal and direction to the camera.
  const Vec4 surface_trace{scene_.ray_time * hit.s, u * hit.s};
  const Vec4 surface_world = scene_.trace_to_world(surface_trace);
  const Vec3 surface_velocity = settings.relativity ? object.world_line.velocity : Vec3{};
  const Vec3 normal = normalize(object.rotation * component_div(hit.shape_normal, object.scale));
  const Vec3 camera_velocity =
      settings.relativity ? scene_.scene->camera.world_line.velocity : Vec3{};
  const ReceivedLeg view =
      receive_leg(surface_world, surface_velocity, scene_.observation_event, camera_velocity);
  const Vec3 to_camera = view.emitted_direction;

  const bool spectral = settings.doppler == DopplerModel::kSpectral;
  const RgbAlbedoSpectrum albedo_spectrum =
      spectral ? RgbAlbedoSpectrum::from_rgb(albedo) : RgbAlbedoSpectrum{};
  const double diffuse = material.glossy ? 1 - material.glossy->specular : 1.0;

  LinearRgb rest{0, 0, 0};     // the classical RGB shading of this geometry (all D = 1)
  LinearRgb shifted{0, 0, 0};  // the surface-frame outgoing radiance (non-spectral models)
  std::array<double, kHeroWavelengths> change{};
  const double camera_factor = spectral_searchlight(d_camera, settings.searchlight);

  for (const ResolvedLight& light : lights_) {
    Incoming in;
    if (!incoming(light, surface_world, surface_velocity, normal, light_sample, in)) continue;
    const double gloss = material.glossy ? glossy_reflectance(*material.glossy, normal,
                                                              in.direction_to_light, to_camera)
                                         : 0.0;
    // Reflected radiance per unit irradiance: albedo / pi (diffuse) plus the glossy lobe.
    auto brdf = [&](double albedo_value) { return diffuse * albedo_value / kPi + gloss; };
    rest.r += brdf(albedo.r) * light.rgb.r * in.weight;
    rest.g += brdf(albedo.g) * light.rgb.g * in.weight;
    rest.b += brdf(albedo.b) * light.rgb.b * in.weight;

    if (spectral) {
      const double light_factor = settings.searchlight == SearchlightModel::kPhysical
                                      ? std::pow(in.doppler, in.doppler_power + 1)
                                      : spectral_searchlight(in.doppler, settings.searchlight);
      for (int i = 0; i < kHeroWavelengths; ++i) {
        const double lambda_camera = wavelengths.lambda[i];
        const double lambda_surface = d_camera * lambda_camera;
        const double lambda_light = in.doppler * lambda_surface;
        const double now = brdf(albedo_spectrum(lambda_surface)) * light_factor *
                           light.spectral(lambda_light) * in.weight;
        const double at_rest =
            brdf(albedo_spectrum(lambda_camera)) * light.spectral(lambda_camera) * in.weight;
        change[i] += camera_factor * now - at_rest;
      }
    } else {
      // The light's colour as the surface sees it, under the chosen model, then reflected.
      const LinearRgb seen =
          received_colour(PointEmission{light.rgb, {}, nullptr}, in.doppler, settings, wavelengths);
      const double scale = settings.searchlight == SearchlightModel::kPhysical
                               ? std::pow(in.doppler, in.doppler_power - 4)  // plane waves: D^2
                               : 1.0;
      shifted.r += brdf(albedo.r) * seen.r * scale * in.weight;
      shifted.g += brdf(albedo.g) * seen.g * scale * in.weight;
      shifted.b += brdf(albedo.b) * seen.b * scale * in.weight;
    }
  }

  if (spectral) {
    const LinearRgb delta = linear_srgb_from_xyz(xyz_from_samples(wavelengths, change));
    return {rest.r + delta.r, rest.g + delta.g, rest.b + delta.b};
  }
  return received_colour(PointEmission{shifted, {}, nullptr}, d_camera, settings, wavelengths);
}

}  // namespace lightcone
