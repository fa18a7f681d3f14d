// A summary of a scene for `lightcone info`: what moves how fast, the Doppler factors and the
// span of emission times the image shows, and an estimate of the memory a render needs.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "lightcone/scene/scene.hpp"

namespace lightcone {

struct BodyInfo {
  std::string name;
  std::string kind;  // "object", "light", "camera", "sky"
  Vec3 velocity;     // in W
  double speed = 0, gamma = 1;
};

struct SceneInfo {
  std::vector<BodyInfo> bodies;  // the camera first, then objects, lights and the sky
  int width = 0, height = 0, samples = 0;
  // The range of the Doppler factor over the image's directions, for what is seen there
  // (every body and the sky, as if unoccluded).
  double doppler_min = 1, doppler_max = 1;
  // The W-times at which the light reaching the image left what it shows (sampled on a grid of
  // rays; absent when every sampled ray sees the sky).
  std::optional<double> emission_time_min, emission_time_max;
  double observation_time = 0;
  std::uint64_t triangles = 0;
  std::uint64_t memory_bytes = 0;  // estimate: meshes, their acceleration structure, images
};

SceneInfo scene_info(const Scene& scene);

}  // namespace lightcone
