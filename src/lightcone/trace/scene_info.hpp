// A summary of a scene for `lightcone info`: what moves how fast, the Doppler factors and the
// span of emission times the image shows, and an estimate of the memory a render needs.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "lightcone/frame/hole_view.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

struct BodyInfo {
  std::string name;
  std::string kind;  // "object", "light", "camera", "sky"
  Vec3 velocity;     // in W
  double speed = 0, gamma = 1;
};

// The black hole as this camera sees it (lengths in the scene's units).
struct HoleInfo {
  double mass = 0;
  double horizon = 0, photon_sphere = 0, isco = 0;  // 2M, 3M, 6M
  double camera_radius = 0;
  // The shadow's angular radius (degrees) for this camera: for its static observer Synge's
  // (1966), aberrated by the camera's velocity (aberration maps circles on the sky to circles).
  double shadow_static_degrees = 0, shadow_degrees = 0;
  // The shift g over the image, exact where sampled: on a grid of curved rays, of the sky, the
  // disk and the bodies they meet, and of every image in view of each body's origin (the
  // shadow left out).
  double shift_min = 1, shift_max = 1;
  bool any_light = false;  // some sampled ray or image sees the sky, the disk or a body
  double mean_image_order = 0;
};

struct SceneInfo {
  std::vector<BodyInfo> bodies;  // the camera first, then objects, lights and the sky
  int width = 0, height = 0, samples = 0;
  // The range of the Doppler factor over the image's directions, for what is seen there
  // (every body and the sky, as if unoccluded); near a hole, HoleInfo's shift.
  double doppler_min = 1, doppler_max = 1;
  // The W-times at which the light reaching the image left what it shows (sampled on a grid of
  // rays, curved near a hole; absent when every sampled ray sees the sky or the disk).
  std::optional<double> emission_time_min, emission_time_max;
  double observation_time = 0;
  std::uint64_t triangles = 0;
  std::uint64_t memory_bytes = 0;  // estimate: meshes, their acceleration structure, images
  std::optional<HoleInfo> hole;
};

// The angular radius (radians) in the camera's frame of the hole's shadow, for a camera at
// `hole.camera_radius` moving relative to its static observer with velocity `beta`.
double shadow_angle_for_camera(const HoleView& hole, const Vec3& beta);

SceneInfo scene_info(const Scene& scene);

// `lightcone info --json`'s line (docs/guide.md), which the Python module's info returns.
std::string scene_info_json(const SceneInfo& info, const Scene& scene);

}  // namespace lightcone
