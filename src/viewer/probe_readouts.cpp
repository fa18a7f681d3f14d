#include "viewer/probe_readouts.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "lightcone/frame/request_rules.hpp"
#include "lightcone/io/locate_json.hpp"

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

void ProbeReadouts::click(const Scene& frame, double x, double y) {
  if (!source_) return;
  if (pending_.valid()) return;  // one at a time: the next click waits for this one
  if (done_.size() >= kMaxProbes) done_.clear();
  refused_.reset();
  if (const auto refused = probe_refused(frame, x, y)) {
    refused_ = *refused;
    std::fprintf(stderr, "lightcone: %s\n", refused->c_str());
    return;
  }
  pending_mark_ = Mark{x, y};
  pending_ = std::async(std::launch::async, [source = source_, frame, x, y] {
    const PixelProbe probe = source(frame, x, y);
    return Done{probe, probe_json(probe, frame), probe_readout(probe, frame), frame.speed_of_light};
  });
}

void ProbeReadouts::clear() {
  done_.clear();
  refused_.reset();
}

void ProbeReadouts::poll() {
  if (!pending_.valid() || pending_.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
    return;
  Done done = pending_.get();
  pending_mark_.reset();
  std::printf("%s\n", done.json.c_str());
  std::fflush(stdout);
  done_.push_back(std::move(done));
}

std::vector<std::string> ProbeReadouts::lines() const {
  std::vector<std::string> out;
  for (std::size_t k = 0; k < done_.size(); ++k)
    for (std::size_t line = 0; line < done_[k].what.size(); ++line)
      out.push_back(line == 0 ? fmt::format("{}: {}", k + 1, done_[k].what[line])
                              : "   " + done_[k].what[line]);
  if (pending_.valid()) out.push_back(fmt::format("{}: ...", done_.size() + 1));
  if (done_.size() == 2)
    out.push_back(probe_ruler(done_[0].probe, done_[1].probe, done_[1].speed_of_light));
  if (refused_) out.push_back(*refused_);
  return out;
}

std::vector<ProbeReadouts::Mark> ProbeReadouts::marks() const {
  std::vector<Mark> out;
  for (const Done& d : done_) out.push_back({d.probe.pixel_x, d.probe.pixel_y});
  if (pending_mark_) out.push_back(*pending_mark_);
  return out;
}

}  // namespace lightcone
