// Lights in motion: the light a lit surface point receives from each light, in the surface's
// rest frame, and what it sends on to the camera (docs/design/light-transport.md).
#pragma once

#include <array>
#include <deque>
#include <optional>
#include <span>
#include <vector>

#include "lightcone/color/doppler_table.hpp"
#include "lightcone/color/rgb_spectrum.hpp"
#include "lightcone/color/spectrum.hpp"
#include "lightcone/frame/emission.hpp"
#include "lightcone/frame/hole_leg_starts.hpp"
#include "lightcone/frame/resolved_scene.hpp"
#include "lightcone/frame/shadow_query.hpp"
#include "lightcone/frame/surface_hit.hpp"
#include "lightcone/physics/hole_world_line.hpp"

namespace lightcone {

class Lighting {
 public:
  // Prepares, for the spectral model, the colour of every fixed albedo of every lit object
  // under every light against the camera's and the light's Doppler factors. Shadows (where the
  // scene asks for them) come from `shadows`, or near a black hole from `curved_shadows`;
  // without one nothing is shadowed.
  // `margin`: the tables cover the camera's factors widened by this much of ln D on each side,
  // so that a renderer can keep them for the next frames (serves()).
  Lighting(const ResolvedScene& scene, const ShadowQuery* shadows,
           const CurvedShadowQuery* curved_shadows = nullptr, double margin = 0);

  // Whether this Lighting, made for an earlier frame, serves `next` as one made for it would:
  // the same Scene object (whose bodies and lights a viewer leaves alone), not near a hole, the
  // same colour, searchlight and delay settings, the same lights' fixed emission events, and
  // camera factors within its tables. follow() then points it at `next`.
  bool serves(const ResolvedScene& next) const;
  void follow(const ResolvedScene& next) { scene_ = &next; }

  // A lit point near a black hole, as the curved camera ray met it: its event (W), and in the
  // static observer's frame there the direction in which its light leaves toward the camera
  // and the surface's velocity. Each light arrives along two null geodesics, directly and round
  // the far side (physics/hole_light_leg.hpp; docs/design/black-hole.md, "Lights").
  // Where given, leg_starts starts each light's legs from the last ones solved to that body.
  struct HoleSurface {
    Vec4 event;
    Vec3 to_camera, local_velocity;
    HoleLegStarts* leg_starts = nullptr;
  };

  // Linear sRGB received at the camera from the lit surface point of `hit`, seen along look
  // direction u with Doppler factor d_camera; `surface` carries the rest-frame albedo (RGB in
  // [0, 1]) and which fixed colour of the material it is. `light_sample` picks points on
  // sphere lights.
  LinearRgb received(const Hit& hit, const Vec3& u, double d_camera, const PointEmission& surface,
                     const std::array<double, 2>& light_sample) const;
  // The same for many points (out[i] for points[i], of the same size), whose shadow rays to each
  // light are asked together, kBatchSize points at a time: neighbouring points of a picture
  // have alike shadow rays, which the tracer follows together.
  struct LitPoint {
    const Hit* hit = nullptr;
    Vec3 u;
    double d_camera = 1;
    PointEmission surface;
    std::array<double, 2> light_sample{0.5, 0.5};
    const HoleSurface* near_hole = nullptr;  // (then u is unused)
  };
  static constexpr std::size_t kBatchSize = 8;
  void received(std::span<const LitPoint> points, std::span<LinearRgb> out) const;

  // What `received` reads, for a renderer that tabulates it (the raster renderer):
  // light l's colour at rest (Y = 1 per unit intensity);
  const LinearRgb& light_rgb(std::size_t l) const { return lights_[l].rgb; }
  // light l's spectrum (spectral model, per unit spectral irradiance factor), which a lit point
  // of fitted albedo reflects (the raster renderer's lit textures);
  double light_spectral(std::size_t l, double lambda_nm) const {
    return lights_[l].spectral(lambda_nm);
  }
  // spectral model: the colour (before searchlight factors, per unit spectral irradiance
  // factor) of fixed colour `colour` of lit object `object` lit by light l, seen with the two
  // factors; whether that light is at rest relative to the object (then d_light is 1);
  Xyz reflected(std::size_t object, int colour, std::size_t l, double d_camera,
                double d_light) const;
  bool co_moving(std::size_t object, std::size_t l) const {
    return object_reflections_[object][0][l].co_moving != nullptr;
  }
  // and light l's own colour seen with factor d (the glossy lobe's).
  Xyz light_seen(std::size_t l, double d) const { return lights_[l].seen(d); }
  // light l's emission event when it does not depend on the lit point (ResolvedLight's
  // fixed_event), and the largest rapidity of a light relative to a lit body (0 for the
  // classical picture): |ln D| on the lights' legs stays within it.
  const std::optional<Vec4>& fixed_emission_event(std::size_t l) const {
    return lights_[l].fixed_event;
  }
  double light_rapidity() const { return light_rapidity_; }
  // The grids of its tables (spectral model), whose factors a renderer that tabulates them reads
  // within: the camera's and the light's factor (reflected), and light l's own colour
  // (light_seen).
  const DopplerGrid& camera_grid() const { return camera_grid_; }
  const DopplerGrid& light_grid() const { return light_grid_; }
  const DopplerGrid& light_seen_grid(std::size_t l) const { return lights_[l].seen.grid(); }

 private:
  struct ResolvedLight {
    const Light* light = nullptr;
    LinearRgb rgb;  // colour at rest, Y = 1 per unit intensity
    std::variant<RgbEmitterSpectrum, BlackbodySpectrum> spectrum;
    // Where its light leaves when that does not depend on the lit point (W): its event on the
    // camera's past light cone ("camera" delay), or where it is at the observation time ("none",
    // and the classical picture); before a sphere light's offset. Unset for the exact delay.
    std::optional<Vec4> fixed_event;
    DopplerXyzTable seen;  // spectral: its colour against the camera-to-light factor
    // Near a black hole (point, spot and sphere lights): its straight coordinate line, relative
    // to the hole.
    std::optional<HoleWorldLine> near_hole;
    double spectral(double lambda_nm) const;
  };
  // What one light delivers to the surface, in the surface's rest frame.
  struct Incoming {
    Vec3 direction_to_light;  // unit, surface rest frame
    double doppler = 1;       // nu_surface / nu_light
    // Irradiance per unit of the light's colour, integrated over wavelength (the colour
    // models other than spectral), and the factor on its spectral radiance read at D lambda
    // (spectral), both under the scene's searchlight model.
    double irradiance = 0;
    double spectral_factor = 0;
  };

  // A shadow ray of `light` from a surface event, with its label from its event at the light's
  // end.
  ShadowRay shadow_ray(const ResolvedLight& light, const Vec4& surface_world, const Vec4& direction,
                       double t_far, const Vec4& light_end) const;
  // Whether the light reaches the surface event (facing it, and within a spot's cone), and if so
  // what it delivers, unless `shadow` (set where shadows are cast) is blocked.
  bool incoming(const ResolvedLight& light, const Vec4& surface_world, const Vec3& surface_velocity,
                const Vec3& normal, const std::array<double, 2>& light_sample, Incoming& out,
                std::optional<ShadowRay>& shadow) const;
  // The same near a black hole, along the ray of image order `order` (0 direct, 1 round the
  // far side), surface_velocity against the static observer there, the shadow path curved;
  // the leg's solve starts from warm_start where given (HoleLegStarts).
  bool incoming_near_hole(const ResolvedLight& light, const Vec4& surface_world,
                          const Vec3& surface_velocity, const Vec3& normal,
                          const std::array<double, 2>& light_sample, int order, Incoming& out,
                          std::optional<CurvedShadowRay>& shadow,
                          RayBetweenStart* warm_start) const;
  // One lit point's state while its lights are summed.
  struct Shading;
  void prepare(const LitPoint& point, Shading& shading) const;
  void add_light(std::size_t l, const Incoming& in, Shading& shading) const;
  LinearRgb finish(const Shading& shading) const;

  const ResolvedScene* scene_;
  const ShadowQuery* shadows_;
  const CurvedShadowQuery* curved_shadows_;
  // The scene's settings with the searchlight off: a light's colour shift as a surface sees it,
  // its irradiance apart.
  RenderSettings unshifted_;
  std::vector<ResolvedLight> lights_;
  LogDopplerRange seen_;  // the factors the camera sees the lit bodies with, margin included
  DopplerGrid camera_grid_, light_grid_;
  RenderSettings settings_;  // as made (serves())
  double light_rapidity_ = 0;
  // The colour of one fixed albedo lit by one light, against the camera's factor (a light at
  // rest relative to the body) or against both factors.
  struct Reflection {
    const DopplerXyzTable* co_moving = nullptr;
    const ReflectionXyzTable* moving = nullptr;
  };
  static Xyz reflected_at(const Reflection& t, const GridStencil& camera, double d_camera,
                          double d_light);
  std::deque<DopplerXyzTable> co_moving_reflections_;
  std::deque<ReflectionXyzTable> reflections_;
  // [object][fixed colour][light] (spectral model, lit objects only).
  std::vector<std::array<std::vector<Reflection>, 2>> object_reflections_;
};

}  // namespace lightcone
