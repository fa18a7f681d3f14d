// OBJ meshes through tinyobjloader: polygons triangulated, v stored as 1 - v (image order), and
// the line of a bad index or statement named. Material libraries (`mtllib`) are never read.
#include <fmt/format.h>
#include <tiny_obj_loader.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "lightcone/io/input_error.hpp"
#include "lightcone/io/mesh_file.hpp"
#include "lightcone/io/mesh_reading.hpp"

namespace lightcone::mesh_io {

namespace fs = std::filesystem;

namespace {

// tinyobjloader does not say which line holds a bad index (it warns once, or silently skips the
// face), so on that error path the text is scanned again to name the line.
[[noreturn]] void fail_obj_index(const fs::path& file, std::string_view text, std::size_t vertices,
                                 std::size_t texcoords) {
  std::size_t v_seen = 0, vt_seen = 0;
  for_each_line(text, [&](std::size_t line, std::string_view s) {
    const auto words = split_words(s);
    if (words.empty()) return true;
    if (words[0] == "v") ++v_seen;
    if (words[0] == "vt") ++vt_seen;
    if (words[0] != "f") return true;
    for (std::size_t w = 1; w < words.size(); ++w) {
      const std::string_view word = words[w];
      const std::size_t slash = word.find('/');
      const std::string_view v = word.substr(0, slash);
      std::string_view vt;
      if (slash != std::string_view::npos) {
        const std::size_t end = word.find('/', slash + 1);
        vt = word.substr(slash + 1, end == std::string_view::npos ? end : end - slash - 1);
      }
      // Positive indices count from the first vertex of the file, negative ones back from the
      // most recent; tinyobjloader resolves positive ones against the final count.
      const auto check = [&](std::string_view token, std::size_t seen, std::size_t total,
                             const char* what, const char* plural) {
        // Like tinyobjloader, read the leading integer and ignore anything after it.
        long long raw = 0;
        if (std::from_chars(token.data(), token.data() + token.size(), raw).ec != std::errc())
          return;
        const long long resolved = raw > 0 ? raw - 1 : static_cast<long long>(seen) + raw;
        if (raw == 0 || resolved < 0 || resolved >= static_cast<long long>(total))
          fail_at(file, line,
                  fmt::format("{} index {} out of range ({} {})", what, raw, total, plural));
      };
      check(v, v_seen, vertices, "vertex", "vertices");
      check(vt, vt_seen, texcoords, "texcoord", "texcoords");
    }
    return true;
  });
  fail(file, "face index out of range");
}

// Names the line of the n-th (0-based) statement starting with `keyword`.
[[noreturn]] void fail_obj_statement(const fs::path& file, std::string_view text,
                                     std::string_view keyword, std::size_t n,
                                     std::string_view what) {
  std::size_t seen = 0;
  for_each_line(text, [&](std::size_t line, std::string_view s) {
    const auto words = split_words(s);
    if (!words.empty() && words[0] == keyword && seen++ == n) fail_at(file, line, what);
    return true;
  });
  fail(file, what);
}

}  // namespace

std::shared_ptr<Mesh> load_obj(const fs::path& file, MeshLoadReport& report) {
  const std::string text = read_whole_file(file);
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  // Parsing from the string (with an empty material text) skips `mtllib`: materials are not
  // needed, and no file an OBJ names is ever opened.
  if (!reader.ParseFromString(text, "", config)) {
    const std::string& err = reader.Error();
    const std::size_t at = err.find("line ");
    std::size_t line = 0;
    if (at != std::string::npos) {
      const char* p = err.data() + at + 5;
      std::from_chars(p, err.data() + err.size(), line);
    }
    const std::string_view first = trim(std::string_view(err).substr(0, err.find('\n')));
    if (err.rfind("Failed parse `f'", 0) == 0 && line > 0)
      fail_at(file, line, "invalid face: zero or malformed vertex index");
    if (line > 0) fail_at(file, line, first);
    fail(file, first.empty() ? "cannot parse OBJ file" : first);
  }
  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  const std::size_t vertex_count = attrib.vertices.size() / 3;
  const std::size_t texcoord_count = attrib.texcoords.size() / 2;
  const std::string& warning = reader.Warning();
  // Normal indices are not used, so their warning is not an error here.
  if (warning.find("Vertex indices out of bounds") != std::string::npos ||
      warning.find("Vertex texcoord indices out of bounds") != std::string::npos ||
      warning.find("invalid vertex index") != std::string::npos)
    fail_obj_index(file, text, vertex_count, texcoord_count);

  for (std::size_t i = 0; i < attrib.vertices.size(); ++i)
    if (!std::isfinite(attrib.vertices[i]))
      fail_obj_statement(file, text, "v", i / 3, "non-finite vertex coordinate");
  for (std::size_t i = 0; i < attrib.texcoords.size(); ++i)
    if (!std::isfinite(attrib.texcoords[i]))
      fail_obj_statement(file, text, "vt", i / 2, "non-finite texture coordinate");

  bool any_uv = false;
  for (const tinyobj::shape_t& shape : reader.GetShapes())
    for (const tinyobj::index_t& index : shape.mesh.indices) {
      if (index.vertex_index < 0 || static_cast<std::size_t>(index.vertex_index) >= vertex_count ||
          index.texcoord_index < -1 ||
          (index.texcoord_index >= 0 &&
           static_cast<std::size_t>(index.texcoord_index) >= texcoord_count))
        fail_obj_index(file, text, vertex_count, texcoord_count);
      any_uv = any_uv || index.texcoord_index >= 0;
    }

  auto mesh = std::make_shared<Mesh>();
  mesh->source = file.string();
  const auto position = [&](int i) {
    const float* p = &attrib.vertices[3 * static_cast<std::size_t>(i)];
    return Vec3{p[0], p[1], p[2]};
  };
  // OBJ indexes positions and texcoords separately; a mesh vertex is a distinct pair of them.
  std::unordered_map<std::uint64_t, std::uint32_t> pair_ids;
  const auto vertex_id = [&](const tinyobj::index_t& index) -> std::uint32_t {
    if (!any_uv) return static_cast<std::uint32_t>(index.vertex_index);
    const std::uint64_t key = (static_cast<std::uint64_t>(index.vertex_index) << 32) |
                              static_cast<std::uint32_t>(index.texcoord_index + 1);
    const auto [it, inserted] =
        pair_ids.try_emplace(key, static_cast<std::uint32_t>(mesh->positions.size()));
    if (inserted) {
      mesh->positions.push_back(position(index.vertex_index));
      if (index.texcoord_index >= 0) {
        const float* t = &attrib.texcoords[2 * static_cast<std::size_t>(index.texcoord_index)];
        mesh->uvs.push_back({t[0], 1 - t[1]});
      } else {
        mesh->uvs.push_back({0, 0});
      }
    }
    return it->second;
  };
  if (!any_uv) {
    mesh->positions.reserve(vertex_count);
    for (std::size_t i = 0; i < vertex_count; ++i) mesh->positions.push_back(position(int(i)));
  }
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    std::size_t offset = 0;
    for (const unsigned int n : shape.mesh.num_face_vertices) {
      if (n == 3) {
        const auto& idx = shape.mesh.indices;
        mesh->triangles.push_back(
            {vertex_id(idx[offset]), vertex_id(idx[offset + 1]), vertex_id(idx[offset + 2])});
      }
      offset += n;
    }
  }
  return finish_mesh(std::move(mesh), file, report);
}

}  // namespace lightcone::mesh_io
