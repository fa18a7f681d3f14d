// Triangle meshes from OBJ, PLY (ASCII and binary) and glTF 2.0 (.gltf, .glb) files.
#pragma once

#include <filesystem>
#include <memory>

#include "lightcone/scene/scene.hpp"

namespace lightcone {

struct MeshLoadReport {
  std::size_t degenerate_triangles_dropped = 0;
};

// Loads every triangle of the file into one mesh (polygons are triangulated; glTF node
// transforms of the default scene are applied). Degenerate triangles (zero area or repeated
// indices) are dropped and counted in `report`. Throws InputError naming the file (and line
// where the format has lines) for unreadable, malformed or empty meshes, out-of-range indices
// and non-finite coordinates.
std::shared_ptr<Mesh> load_mesh_file(const std::filesystem::path& file, MeshLoadReport& report);

}  // namespace lightcone
