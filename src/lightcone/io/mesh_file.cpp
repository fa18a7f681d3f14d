// Mesh files: OBJ (mesh_obj.cpp), PLY (mesh_ply.cpp) and glTF 2.0 (mesh_gltf.cpp) by their
// extension. Every format ends in finish_mesh(), which checks the result and drops degenerate
// triangles.
//
// Texture coordinates are stored in image order, as the renderer samples them (and as glTF has
// them): (0, 0) is the top-left corner and v grows downwards. OBJ and PLY put (0, 0) at the
// bottom-left, so their v is stored as 1 - v.
#include "lightcone/io/mesh_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "lightcone/io/input_error.hpp"
#include "lightcone/io/input_file.hpp"
#include "lightcone/io/mesh_reading.hpp"

namespace lightcone {
namespace mesh_io {

namespace fs = std::filesystem;

namespace {

// Zero area, or so thin that its normal is numerically meaningless.
bool degenerate(const Mesh& mesh, const std::array<std::uint32_t, 3>& t) {
  if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) return true;
  const Vec3& a = mesh.positions[t[0]];
  const Vec3 e1 = mesh.positions[t[1]] - a, e2 = mesh.positions[t[2]] - a;
  const Vec3 e3 = e2 - e1;
  const double scale2 = std::max({dot(e1, e1), dot(e2, e2), dot(e3, e3)});
  return length(cross(e1, e2)) <= 1e-12 * scale2;
}

}  // namespace

[[noreturn]] void fail(const fs::path& file, std::string_view what) {
  throw InputError(fmt::format("{}: {}", file.string(), what));
}

[[noreturn]] void fail_at(const fs::path& file, std::size_t line, std::string_view what) {
  throw InputError(fmt::format("{}:{}: {}", file.string(), line, what));
}

std::string read_whole_file(const fs::path& file) {
  return read_input_file(file, "mesh file", kMaxAssetFileBytes);
}

// The formats report bad indices and coordinates with their own context; these checks only
// guarantee the invariants the renderer relies on.
std::shared_ptr<Mesh> finish_mesh(std::shared_ptr<Mesh> mesh, const fs::path& file,
                                  MeshLoadReport& report) {
  for (std::size_t i = 0; i < mesh->positions.size(); ++i)
    if (!finite(mesh->positions[i]))
      fail(file, fmt::format("vertex {} has a non-finite coordinate", i));
  if (!mesh->uvs.empty() && mesh->uvs.size() != mesh->positions.size())
    fail(file, "texture coordinates do not match the vertices");
  std::size_t kept = 0;
  for (const auto& t : mesh->triangles) {
    for (std::uint32_t index : t)
      if (index >= mesh->positions.size())
        fail(file, fmt::format("vertex index {} out of range ({} vertices)", index,
                               mesh->positions.size()));
    if (!degenerate(*mesh, t)) mesh->triangles[kept++] = t;
  }
  const std::size_t dropped = mesh->triangles.size() - kept;
  mesh->triangles.resize(kept);
  report.degenerate_triangles_dropped = dropped;
  if (kept == 0) {
    if (dropped > 0)
      fail(file, fmt::format("mesh has no triangles (all {} are degenerate)", dropped));
    fail(file, "mesh has no triangles");
  }
  return mesh;
}

bool finite(const Vec3& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split_words(std::string_view s) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    const std::size_t start = i;
    while (i < s.size() && !std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    if (i > start) words.push_back(s.substr(start, i - start));
  }
  return words;
}

}  // namespace mesh_io

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

std::shared_ptr<Mesh> load_mesh_file(const std::filesystem::path& file, MeshLoadReport& report,
                                     const MeshLoadOptions& options) {
  using namespace mesh_io;
  report = {};
  const std::string ext = lower(file.extension().string());
  if (ext == ".obj") return load_obj(file, report);
  if (ext == ".ply") return load_ply(file, report);
  if (ext == ".gltf") return load_gltf(file, false, report, options);
  if (ext == ".glb") return load_gltf(file, true, report, options);
  fail(file, fmt::format("unsupported mesh format '{}' (use .obj, .ply, .gltf or .glb)", ext));
}

}  // namespace lightcone
