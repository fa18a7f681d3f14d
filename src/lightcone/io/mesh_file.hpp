// Triangle meshes from OBJ, PLY (ASCII and binary) and glTF 2.0 (.gltf, .glb) files.
#pragma once

#include <filesystem>
#include <memory>

#include "lightcone/scene/scene.hpp"

namespace lightcone {

struct MeshLoadOptions {
  // Whether the files a mesh file names (a glTF's buffer and image uris) may lie outside the
  // mesh file's own folder (after `..` and symbolic links are resolved; an absolute uri is
  // outside). Off, such a reference is refused without looking at the file it names.
  bool allow_outside = false;
};

struct MeshLoadReport {
  std::size_t degenerate_triangles_dropped = 0;
};

// Loads every triangle of the file into one mesh (polygons are triangulated; glTF node
// transforms of the default scene are applied). Degenerate triangles (zero area or repeated
// indices) are dropped and counted in `report`. Throws InputError naming the file (and line
// where the format has lines) for unreadable, malformed or empty meshes, out-of-range indices
// and non-finite coordinates.
//
// The files a glTF names are read as the mesh file itself is (regular files only, within
// kMaxAssetFileBytes) and only inside its folder unless `options` allow others; a refused
// reference names the mesh file, the uri (percent-decoded) and why, and never says whether or
// how large a file outside the folder is. OBJ material libraries (`mtllib`) are not read.
std::shared_ptr<Mesh> load_mesh_file(const std::filesystem::path& file, MeshLoadReport& report,
                                     const MeshLoadOptions& options = {});

}  // namespace lightcone
