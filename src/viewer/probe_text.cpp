#include "viewer/probe_text.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

namespace lightcone {
namespace {

std::string triple(const Vec3& v) {
  return fmt::format("({:.7g}, {:.7g}, {:.7g})", v.x, v.y, v.z);
}

}  // namespace

std::vector<std::string> probe_readout(const PixelProbe& probe, const Scene& scene) {
  // Times in the scene's units (the model's are c t), as locate prints them.
  const double c = scene.speed_of_light;
  const std::string shift = fmt::format("{} {:.7g}", scene.black_hole ? "g" : "D", probe.doppler);
  const std::string order = scene.black_hole ? fmt::format(", order {}", probe.order) : "";
  switch (probe.meets) {
    case ProbeMeets::kObject:
      return {fmt::format("{} at {}", scene.objects[probe.object].name, triple(probe.point)),
              fmt::format("emitted at t = {:.9g}, its clock {:.9g}, {}{}", *probe.emission_time / c,
                          *probe.emission_proper_time / c, shift, order)};
    case ProbeMeets::kDisk:
      return {fmt::format("the disk at r = {:.7g}", probe.disk_radius),
              fmt::format("emitted at t = {:.9g}, {}{}", *probe.emission_time / c, shift, order)};
    case ProbeMeets::kSky:
      return {fmt::format("the sky, from {}", triple(probe.sky_direction)),
              fmt::format("{}{}", shift, order)};
    case ProbeMeets::kShadow:
      break;
  }
  return {"nothing: the shadow (the ray falls into the hole)"};
}

std::string probe_ruler(const PixelProbe& first, const PixelProbe& second, double speed_of_light) {
  // The angle from the cross and dot products: exact for small angles, where acos is not.
  const double angle = std::atan2(length(cross(first.direction, second.direction)),
                                  dot(first.direction, second.direction)) *
                       180 / std::numbers::pi;
  std::string ruler = fmt::format("1 to 2: {:.7g} degrees apart", angle);
  if (first.emission_time && second.emission_time)
    ruler += fmt::format("; emitted {:.9g} apart in t",
                         (*second.emission_time - *first.emission_time) / speed_of_light);
  return ruler;
}

std::vector<std::string> probe_lines(const std::vector<PixelProbe>& probes, const Scene& scene) {
  std::vector<std::string> out;
  for (std::size_t k = 0; k < probes.size(); ++k) {
    const std::vector<std::string> readout = probe_readout(probes[k], scene);
    for (std::size_t line = 0; line < readout.size(); ++line)
      out.push_back(line == 0 ? fmt::format("{}: {}", k + 1, readout[line])
                              : "   " + readout[line]);
  }
  if (probes.size() == 2) out.push_back(probe_ruler(probes[0], probes[1], scene.speed_of_light));
  return out;
}

}  // namespace lightcone
