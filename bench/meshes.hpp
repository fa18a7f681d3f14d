// Meshes and scenes the benchmarks share.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "lightcone/scene/scene.hpp"

namespace lightcone::bench {

// An icosahedron subdivided `levels` times, on the unit sphere: 20 * 4^levels triangles.
inline std::shared_ptr<const Mesh> icosphere(int levels) {
  auto mesh = std::make_shared<Mesh>();
  const double t = (1 + std::sqrt(5.0)) / 2;
  for (const Vec3& p : {Vec3{-1, t, 0}, Vec3{1, t, 0}, Vec3{-1, -t, 0}, Vec3{1, -t, 0},
                        Vec3{0, -1, t}, Vec3{0, 1, t}, Vec3{0, -1, -t}, Vec3{0, 1, -t},
                        Vec3{t, 0, -1}, Vec3{t, 0, 1}, Vec3{-t, 0, -1}, Vec3{-t, 0, 1}})
    mesh->positions.push_back(normalize(p));
  mesh->triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                     {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                     {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                     {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
    const auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::minmax(a, b);
      if (auto it = midpoints.find(key); it != midpoints.end()) return it->second;
      mesh->positions.push_back(normalize(mesh->positions[a] + mesh->positions[b]));
      return midpoints[key] = static_cast<std::uint32_t>(mesh->positions.size() - 1);
    };
    std::vector<std::array<std::uint32_t, 3>> finer;
    for (const auto& [a, b, c] : mesh->triangles) {
      const auto ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      finer.insert(finer.end(), {{a, ab, ca}, {b, bc, ab}, {c, ca, bc}, {ab, bc, ca}});
    }
    mesh->triangles = std::move(finer);
  }
  return mesh;
}

// `count` instances of one ~1280-triangle mesh, moving in random directions at up to 0.9c.
inline Scene swarm_scene(int count, bool relativity, int width = 1920, int height = 1080) {
  static const std::shared_ptr<const Mesh> mesh = icosphere(3);
  Scene s;
  s.camera.width = width;
  s.camera.height = height;
  s.camera.fov_degrees = 70;
  s.render.relativity = relativity;
  s.render.doppler = DopplerModel::kOff;  // geometry only, like the street comparison
  s.render.searchlight = SearchlightModel::kOff;
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < count; ++i) {
    Object o;
    o.name = "body-" + std::to_string(i);
    o.shape = MeshShape{mesh};
    o.world_line.position = {u(rng) * 40, u(rng) * 22, -30 + u(rng) * 25};
    Vec3 dir{u(rng), u(rng), u(rng)};
    o.world_line.velocity = normalize(dir) * (0.9 * std::abs(u(rng)));
    o.scale = {1.2, 1.2, 1.2};
    o.material.pattern = SolidColor{{0.8f, 0.6f, 0.3f}};
    s.objects.push_back(o);
  }
  s.sky.pattern = SolidColor{{0.05f, 0.05f, 0.1f}};
  return s;
}

}  // namespace lightcone::bench
