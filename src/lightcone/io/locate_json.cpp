#include "lightcone/io/locate_json.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

namespace lightcone {
namespace {

nlohmann::ordered_json to_json(const Vec3& v) {
  return nlohmann::json::array({v.x, v.y, v.z});
}

bool finite(const Vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

bool locate_result_is_finite(const LocateResult& r) {
  return finite(r.direction) && std::isfinite(r.doppler) &&
         (!r.in_view || (std::isfinite(r.pixel_x) && std::isfinite(r.pixel_y))) &&
         (!r.emission_time || std::isfinite(*r.emission_time)) &&
         (!r.emission_proper_time || std::isfinite(*r.emission_proper_time)) &&
         (!r.emission_position || finite(*r.emission_position)) &&
         (!r.distance || std::isfinite(*r.distance));
}

std::string locate_json(const LocateResult& r, const Scene& scene) {
  nlohmann::ordered_json out = {{"pixel", {r.pixel_x, r.pixel_y}},
                                {"direction", to_json(r.direction)},
                                {"emission_time", nullptr},
                                {"emission_position", nullptr},
                                {"emission_proper_time", nullptr},
                                {"distance", nullptr},
                                {"in_view", r.in_view},
                                {"doppler", r.doppler}};
  if (!r.in_view) out["pixel"] = nullptr;  // behind the camera or outside the image
  if (scene.black_hole && r.images.empty()) {
    // No light from the point reaches the camera (an object's point inside the horizon then):
    // nothing is seen, so there is no direction and no shift to give.
    out["direction"] = nullptr;
    out["doppler"] = nullptr;
  }
  // Times in the scene's units (the model's are c t).
  const double c = scene.speed_of_light;
  if (r.emission_time) out["emission_time"] = *r.emission_time / c;
  if (r.emission_proper_time) out["emission_proper_time"] = *r.emission_proper_time / c;
  if (r.emission_position) out["emission_position"] = to_json(*r.emission_position);
  if (r.distance) out["distance"] = *r.distance;
  if (scene.black_hole) {
    // Every image, the primary first (whose pixel and direction are the fields above).
    nlohmann::ordered_json images = nlohmann::ordered_json::array();
    for (const LocateImage& image : r.images) {
      nlohmann::ordered_json one = {{"order", image.order},
                                    {"pixel", {image.pixel_x, image.pixel_y}},
                                    {"direction", to_json(image.direction)},
                                    {"emission_time", nullptr},
                                    {"emission_position", nullptr},
                                    {"emission_proper_time", nullptr},
                                    {"distance", nullptr},
                                    {"in_view", image.in_view},
                                    {"g", image.shift}};
      if (!image.in_view) one["pixel"] = nullptr;
      if (image.emission_time) one["emission_time"] = *image.emission_time / c;
      if (image.emission_position) one["emission_position"] = to_json(*image.emission_position);
      if (image.emission_proper_time) one["emission_proper_time"] = *image.emission_proper_time / c;
      if (image.distance) one["distance"] = *image.distance;
      images.push_back(one);
    }
    out["images"] = images;
  }
  return out.dump();
}

std::string probe_json(const PixelProbe& p, const Scene& scene) {
  const char* meets = p.meets == ProbeMeets::kObject ? "object"
                      : p.meets == ProbeMeets::kSky  ? "sky"
                      : p.meets == ProbeMeets::kDisk ? "disk"
                                                     : "shadow";
  nlohmann::ordered_json out = {{"pixel", {p.pixel_x, p.pixel_y}},
                                {"direction", to_json(p.direction)},
                                {"meets", meets},
                                {"object", nullptr},
                                {"point", nullptr},
                                {"sky", nullptr},
                                {"disk", nullptr},
                                {"emission_time", nullptr},
                                {"emission_position", nullptr},
                                {"emission_proper_time", nullptr},
                                {"distance", nullptr},
                                {"doppler", p.doppler}};
  if (p.meets == ProbeMeets::kObject) {
    out["object"] = scene.objects[p.object].name;
    out["point"] = to_json(p.point);
  }
  if (p.meets == ProbeMeets::kSky) out["sky"] = {{"direction", to_json(p.sky_direction)}};
  if (p.meets == ProbeMeets::kDisk) out["disk"] = {{"radius", p.disk_radius}};
  // Times in the scene's units (the model's are c t).
  const double c = scene.speed_of_light;
  if (p.emission_time) out["emission_time"] = *p.emission_time / c;
  if (p.emission_position) out["emission_position"] = to_json(*p.emission_position);
  if (p.emission_proper_time) out["emission_proper_time"] = *p.emission_proper_time / c;
  if (p.distance) out["distance"] = *p.distance;
  if (scene.black_hole) out["order"] = p.order;
  return out.dump();
}

}  // namespace lightcone
