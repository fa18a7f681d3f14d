// Lights in motion: the light a lit surface point receives from each light, in the surface's
// rest frame, and what it sends on to the camera (docs/design/light-transport.md).
#pragma once

#include <array>
#include <vector>

#include "lightcone/color/rgb_spectrum.hpp"
#include "lightcone/color/spectrum.hpp"
#include "lightcone/color/wavelengths.hpp"
#include "lightcone/render/resolved_scene.hpp"
#include "lightcone/render/tracer.hpp"

namespace lightcone {

class Lighting {
 public:
  Lighting(const ResolvedScene& scene, const Tracer& tracer);

  // Linear sRGB received at the camera from the lit surface point of `hit`, seen along look
  // direction u with Doppler factor d_camera, for the surface's rest-frame albedo (RGB in
  // [0, 1]). `light_sample` picks points on sphere lights.
  LinearRgb received(const Hit& hit, const Vec3& u, double d_camera, const LinearRgb& albedo,
                     const SampledWavelengths& wavelengths,
                     const std::array<double, 2>& light_sample) const;

 private:
  struct ResolvedLight {
    const Light* light = nullptr;
    LinearRgb rgb;  // colour at rest, Y = 1 per unit intensity
    std::variant<RgbIlluminantSpectrum, BlackbodySpectrum> spectrum;
    Vec4 camera_event;  // its event on the camera's past light cone (W), for "camera" delay
    double spectral(double lambda_nm) const;
  };
  // What one light delivers to the surface, in the surface's rest frame.
  struct Incoming {
    Vec3 direction_to_light;  // unit, surface rest frame
    double doppler = 1;       // nu_surface / nu_light
    double weight = 0;        // irradiance per unit of the light's colour at D = 1, before D^n
    int doppler_power = 4;    // integrated irradiance scales as D^power (D^(power+1) spectral)
  };

  bool incoming(const ResolvedLight& light, const Vec4& surface_world, const Vec3& surface_velocity,
                const Vec3& normal, const std::array<double, 2>& light_sample, Incoming& out) const;

  const ResolvedScene& scene_;
  const Tracer& tracer_;
  std::vector<ResolvedLight> lights_;
};

}  // namespace lightcone
