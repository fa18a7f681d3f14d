// Mesh files: OBJ through tinyobjloader, glTF 2.0 through tinygltf, PLY through the compact reader
// below (Debian packages no PLY library). Every format ends in finish_mesh(), which checks the
// result and drops degenerate triangles.
//
// Texture coordinates are stored in image order, as the renderer samples them (and as glTF has
// them): (0, 0) is the top-left corner and v grows downwards. OBJ and PLY put (0, 0) at the
// bottom-left, so their v is stored as 1 - v.
#include "lightcone/io/mesh_file.hpp"

#include <fmt/format.h>
#include <tiny_gltf.h>
#include <tiny_obj_loader.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "lightcone/io/input_error.hpp"
#include "lightcone/io/input_file.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const fs::path& file, std::string_view what) {
  throw InputError(fmt::format("{}: {}", file.string(), what));
}

[[noreturn]] void fail_at(const fs::path& file, std::size_t line, std::string_view what) {
  throw InputError(fmt::format("{}:{}: {}", file.string(), line, what));
}

std::string read_whole_file(const fs::path& file) {
  return read_input_file(file, "mesh file", kMaxAssetFileBytes);
}

bool finite(const Vec3& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

// Zero area, or so thin that its normal is numerically meaningless.
bool degenerate(const Mesh& mesh, const std::array<std::uint32_t, 3>& t) {
  if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) return true;
  const Vec3& a = mesh.positions[t[0]];
  const Vec3 e1 = mesh.positions[t[1]] - a, e2 = mesh.positions[t[2]] - a;
  const Vec3 e3 = e2 - e1;
  const double scale2 = std::max({dot(e1, e1), dot(e2, e2), dot(e3, e3)});
  return length(cross(e1, e2)) <= 1e-12 * scale2;
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

// Calls f(line_number, line) for each line of `text`, without the line terminator; f returns
// false to stop.
template <class F>
void for_each_line(std::string_view text, F&& f) {
  std::size_t line = 0, pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view s = text.substr(pos, end - pos);
    if (!s.empty() && s.back() == '\r') s.remove_suffix(1);
    if (!f(++line, s)) return;
    pos = end + 1;
  }
}

template <class T>
bool parse_number(std::string_view s, T& value) {
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  return ec == std::errc() && end == s.data() + s.size();
}

// ---------------------------------------------------------------------------------------------
// OBJ

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

// ---------------------------------------------------------------------------------------------
// PLY

enum class PlyType { i8, u8, i16, u16, i32, u32, f32, f64 };

std::optional<PlyType> ply_type(std::string_view name) {
  static constexpr std::pair<std::string_view, PlyType> names[] = {
      {"char", PlyType::i8},    {"int8", PlyType::i8},     {"uchar", PlyType::u8},
      {"uint8", PlyType::u8},   {"short", PlyType::i16},   {"int16", PlyType::i16},
      {"ushort", PlyType::u16}, {"uint16", PlyType::u16},  {"int", PlyType::i32},
      {"int32", PlyType::i32},  {"uint", PlyType::u32},    {"uint32", PlyType::u32},
      {"float", PlyType::f32},  {"float32", PlyType::f32}, {"double", PlyType::f64},
      {"float64", PlyType::f64}};
  for (const auto& [n, t] : names)
    if (n == name) return t;
  return std::nullopt;
}

std::size_t ply_size(PlyType t) {
  switch (t) {
    case PlyType::i8:
    case PlyType::u8:
      return 1;
    case PlyType::i16:
    case PlyType::u16:
      return 2;
    case PlyType::i32:
    case PlyType::u32:
    case PlyType::f32:
      return 4;
    case PlyType::f64:
      return 8;
  }
  return 0;
}

bool ply_integral(PlyType t) {
  return t != PlyType::f32 && t != PlyType::f64;
}

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::f32;  // of the items, for a list
  bool list = false;
  PlyType count_type = PlyType::u8;
};

struct PlyElement {
  std::string name;
  std::size_t count = 0;
  std::size_t line = 0;  // of its declaration
  std::vector<PlyProperty> properties;

  int find(std::string_view property) const {
    for (std::size_t i = 0; i < properties.size(); ++i)
      if (properties[i].name == property) return static_cast<int>(i);
    return -1;
  }
};

enum class PlyFormat { ascii, binary_little_endian, binary_big_endian };

struct PlyHeader {
  PlyFormat format = PlyFormat::ascii;
  std::vector<PlyElement> elements;
  std::size_t body_offset = 0;  // byte offset of the data after end_header
  std::size_t lines = 0;        // line count of the header
};

PlyHeader parse_ply_header(const fs::path& file, std::string_view data) {
  PlyHeader header;
  bool have_format = false, ended = false;
  std::size_t pos = 0, line = 0;
  while (pos < data.size() && !ended) {
    std::size_t end = data.find('\n', pos);
    if (end == std::string_view::npos) end = data.size();
    std::string_view s = data.substr(pos, end - pos);
    pos = end + 1;
    ++line;
    if (!s.empty() && s.back() == '\r') s.remove_suffix(1);
    const auto words = split_words(s);
    if (line == 1) {
      if (words.size() != 1 || words[0] != "ply")
        fail_at(file, line, "not a PLY file (the first line must be 'ply')");
      continue;
    }
    if (words.empty() || words[0] == "comment" || words[0] == "obj_info") continue;
    const std::string_view key = words[0];
    if (key == "format") {
      if (words.size() != 3) fail_at(file, line, "expected 'format <type> <version>'");
      if (words[1] == "ascii")
        header.format = PlyFormat::ascii;
      else if (words[1] == "binary_little_endian")
        header.format = PlyFormat::binary_little_endian;
      else if (words[1] == "binary_big_endian")
        header.format = PlyFormat::binary_big_endian;
      else
        fail_at(file, line, fmt::format("unknown PLY format '{}'", words[1]));
      have_format = true;
    } else if (key == "element") {
      PlyElement element;
      if (words.size() != 3 || !parse_number(words[2], element.count))
        fail_at(file, line, "expected 'element <name> <count>'");
      element.name = std::string(words[1]);
      element.line = line;
      header.elements.push_back(std::move(element));
    } else if (key == "property") {
      if (header.elements.empty()) fail_at(file, line, "property before any element");
      PlyProperty property;
      if (words.size() == 5 && words[1] == "list") {
        const auto count_type = ply_type(words[2]);
        const auto item_type = ply_type(words[3]);
        if (!count_type || !ply_integral(*count_type))
          fail_at(file, line, fmt::format("invalid list count type '{}'", words[2]));
        if (!item_type) fail_at(file, line, fmt::format("unknown property type '{}'", words[3]));
        property.list = true;
        property.count_type = *count_type;
        property.type = *item_type;
        property.name = std::string(words[4]);
      } else if (words.size() == 3) {
        const auto type = ply_type(words[1]);
        if (!type) fail_at(file, line, fmt::format("unknown property type '{}'", words[1]));
        property.type = *type;
        property.name = std::string(words[2]);
      } else {
        fail_at(file, line,
                "expected 'property <type> <name>' or 'property list <type> <type> <name>'");
      }
      header.elements.back().properties.push_back(std::move(property));
    } else if (key == "end_header") {
      if (words.size() != 1) fail_at(file, line, "unexpected text after 'end_header'");
      if (!have_format) fail_at(file, line, "the PLY header has no 'format' line");
      ended = true;
    } else {
      fail_at(file, line, fmt::format("unexpected '{}' in the PLY header", key));
    }
  }
  if (!ended) fail(file, "the PLY header has no 'end_header' line");
  header.body_offset = std::min(pos, data.size());
  header.lines = line;
  return header;
}

// Whitespace-separated values, one element per line (as every PLY writer does).
class PlyAsciiReader {
 public:
  PlyAsciiReader(const fs::path& file, std::string_view body, std::size_t first_line)
      : file_(file), body_(body), line_(first_line - 1) {}

  void begin(const PlyElement& element, std::size_t index) {
    element_ = &element;
    for (;;) {
      if (pos_ >= body_.size())
        fail_at(file_, line_,
                fmt::format("unexpected end of file: {} of {} '{}' elements read", index,
                            element.count, element.name));
      std::size_t end = body_.find('\n', pos_);
      if (end == std::string_view::npos) end = body_.size();
      words_ = split_words(body_.substr(pos_, end - pos_));
      pos_ = end + 1;
      ++line_;
      next_ = 0;
      if (!words_.empty()) return;
    }
  }

  double value(PlyType type) {
    if (next_ >= words_.size())
      fail(fmt::format("too few values for element '{}'", element_->name));
    const std::string_view word = words_[next_++];
    bool ok;
    double v = 0;
    if (ply_integral(type)) {
      long long i = 0;
      ok = parse_number(word, i);
      v = static_cast<double>(i);
    } else {
      ok = parse_number(word, v);
    }
    if (!ok) fail(fmt::format("invalid number '{}'", word));
    return v;
  }

  void end() {
    if (next_ != words_.size())
      fail(fmt::format("too many values for element '{}'", element_->name));
  }

  [[noreturn]] void fail(std::string_view what) const { fail_at(file_, line_, what); }

 private:
  const fs::path& file_;
  std::string_view body_;
  std::size_t pos_ = 0, line_;
  std::vector<std::string_view> words_;
  std::size_t next_ = 0;
  const PlyElement* element_ = nullptr;
};

class PlyBinaryReader {
 public:
  PlyBinaryReader(const fs::path& file, std::string_view body, bool big_endian)
      : file_(file), body_(body), big_endian_(big_endian) {}

  void begin(const PlyElement& element, std::size_t index) {
    element_ = &element;
    index_ = index;
  }

  double value(PlyType type) {
    const std::size_t size = ply_size(type);
    if (body_.size() - pos_ < size)
      fail_plain(fmt::format("unexpected end of file: {} of {} '{}' elements read", index_,
                             element_->count, element_->name));
    unsigned char bytes[8];
    std::memcpy(bytes, body_.data() + pos_, size);
    pos_ += size;
    if (big_endian_ != (std::endian::native == std::endian::big)) std::reverse(bytes, bytes + size);
    switch (type) {
      case PlyType::i8:
        return load<std::int8_t>(bytes);
      case PlyType::u8:
        return load<std::uint8_t>(bytes);
      case PlyType::i16:
        return load<std::int16_t>(bytes);
      case PlyType::u16:
        return load<std::uint16_t>(bytes);
      case PlyType::i32:
        return load<std::int32_t>(bytes);
      case PlyType::u32:
        return load<std::uint32_t>(bytes);
      case PlyType::f32:
        return load<float>(bytes);
      case PlyType::f64:
        return load<double>(bytes);
    }
    return 0;
  }

  void end() {}

  [[noreturn]] void fail(std::string_view what) const {
    fail_plain(fmt::format("{} {}: {}", element_->name, index_, what));
  }

 private:
  template <class T>
  static double load(const unsigned char* bytes) {
    T v;
    std::memcpy(&v, bytes, sizeof v);
    return static_cast<double>(v);
  }
  [[noreturn]] void fail_plain(std::string_view what) const { lightcone::fail(file_, what); }

  const fs::path& file_;
  std::string_view body_;
  bool big_endian_;
  std::size_t pos_ = 0;
  const PlyElement* element_ = nullptr;
  std::size_t index_ = 0;
};

template <class Reader>
void read_ply_body(Reader& in, const PlyHeader& header, Mesh& mesh, std::size_t& short_faces) {
  std::size_t vertex_count = 0;
  for (const PlyElement& e : header.elements)
    if (e.name == "vertex") vertex_count = e.count;
  std::vector<std::uint32_t> polygon;
  for (const PlyElement& element : header.elements) {
    const bool is_vertex = element.name == "vertex", is_face = element.name == "face";
    int x = -1, y = -1, z = -1, u = -1, v = -1, indices = -1;
    if (is_vertex) {
      x = element.find("x"), y = element.find("y"), z = element.find("z");
      static constexpr std::pair<const char*, const char*> uv_names[] = {
          {"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}};
      for (const auto& [un, vn] : uv_names)
        if (u < 0 && element.find(un) >= 0 && element.find(vn) >= 0)
          u = element.find(un), v = element.find(vn);
      // The declared count may be anything: reserve no more than a file could plausibly hold
      // at once; a count beyond the data ends at the end of the file with an error.
      const std::size_t plausible = std::min<std::size_t>(element.count, std::size_t{1} << 20);
      mesh.positions.reserve(plausible);
      if (u >= 0) mesh.uvs.reserve(plausible);
    }
    if (is_face) {
      indices = element.find("vertex_indices");
      if (indices < 0) indices = element.find("vertex_index");
    }
    for (std::size_t n = 0; n < element.count; ++n) {
      in.begin(element, n);
      Vec3 p;
      std::array<float, 2> uv{};
      for (int k = 0; k < static_cast<int>(element.properties.size()); ++k) {
        const PlyProperty& property = element.properties[k];
        if (property.list) {
          const double count = in.value(property.count_type);
          if (count < 0) in.fail(fmt::format("negative list length {}", count));
          if (k == indices) polygon.clear();
          for (std::size_t i = 0; i < static_cast<std::size_t>(count); ++i) {
            const double index = in.value(property.type);
            if (k != indices) continue;
            if (!(index >= 0 && index < static_cast<double>(vertex_count)) ||
                index != std::floor(index))
              in.fail(
                  fmt::format("vertex index {} out of range ({} vertices)", index, vertex_count));
            polygon.push_back(static_cast<std::uint32_t>(index));
          }
          continue;
        }
        const double value = in.value(property.type);
        if (k == x) p.x = value;
        if (k == y) p.y = value;
        if (k == z) p.z = value;
        if (k == u) uv[0] = static_cast<float>(value);
        if (k == v) uv[1] = static_cast<float>(1 - value);
      }
      in.end();
      if (is_vertex) {
        if (!finite(p)) in.fail("non-finite vertex coordinate");
        if (u >= 0 && !(std::isfinite(uv[0]) && std::isfinite(uv[1])))
          in.fail("non-finite texture coordinate");
        mesh.positions.push_back(p);
        if (u >= 0) mesh.uvs.push_back(uv);
      }
      if (is_face) {
        if (polygon.size() < 3) ++short_faces;
        for (std::size_t i = 2; i < polygon.size(); ++i)
          mesh.triangles.push_back({polygon[0], polygon[i - 1], polygon[i]});
      }
    }
  }
}

std::shared_ptr<Mesh> load_ply(const fs::path& file, MeshLoadReport& report) {
  const std::string data = read_whole_file(file);
  const PlyHeader header = parse_ply_header(file, data);
  const PlyElement* vertex = nullptr;
  for (const PlyElement& e : header.elements) {
    if (e.name == "vertex") {
      vertex = &e;
      for (const char* c : {"x", "y", "z"}) {
        const int i = e.find(c);
        if (i < 0 || e.properties[i].list)
          fail_at(file, e.line, fmt::format("element 'vertex' has no scalar property '{}'", c));
      }
    }
    if (e.name == "face") {
      int i = e.find("vertex_indices");
      if (i < 0) i = e.find("vertex_index");
      if (i < 0 || !e.properties[i].list)
        fail_at(file, e.line, "element 'face' has no list property 'vertex_indices'");
      if (!ply_integral(e.properties[i].type))
        fail_at(file, e.line, "face vertex indices must have an integer type");
    }
  }
  if (vertex == nullptr) fail(file, "the PLY header declares no 'vertex' element");
  if (vertex->count > std::numeric_limits<std::uint32_t>::max())
    fail_at(file, vertex->line, "too many vertices");

  auto mesh = std::make_shared<Mesh>();
  mesh->source = file.string();
  const std::string_view body = std::string_view(data).substr(header.body_offset);
  std::size_t short_faces = 0;
  if (header.format == PlyFormat::ascii) {
    PlyAsciiReader in(file, body, header.lines + 1);
    read_ply_body(in, header, *mesh, short_faces);
  } else {
    PlyBinaryReader in(file, body, header.format == PlyFormat::binary_big_endian);
    read_ply_body(in, header, *mesh, short_faces);
  }
  finish_mesh(mesh, file, report);
  // Faces with fewer than three corners have no area either.
  report.degenerate_triangles_dropped += short_faces;
  return mesh;
}

// ---------------------------------------------------------------------------------------------
// glTF 2.0

using Mat4 = std::array<double, 16>;  // column-major, as glTF stores it

constexpr Mat4 identity4 = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

Mat4 operator*(const Mat4& a, const Mat4& b) {
  Mat4 r{};
  for (int col = 0; col < 4; ++col)
    for (int row = 0; row < 4; ++row)
      for (int k = 0; k < 4; ++k) r[col * 4 + row] += a[k * 4 + row] * b[col * 4 + k];
  return r;
}

Vec3 transform_point(const Mat4& m, const Vec3& p) {
  return {m[0] * p.x + m[4] * p.y + m[8] * p.z + m[12],
          m[1] * p.x + m[5] * p.y + m[9] * p.z + m[13],
          m[2] * p.x + m[6] * p.y + m[10] * p.z + m[14]};
}

double determinant3(const Mat4& m) {
  return m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) +
         m[8] * (m[1] * m[6] - m[5] * m[2]);
}

// Local transform of a node: its matrix, or T R S.
Mat4 node_transform(const tinygltf::Node& node) {
  if (node.matrix.size() == 16) {
    Mat4 m;
    std::copy(node.matrix.begin(), node.matrix.end(), m.begin());
    return m;
  }
  Mat4 m = identity4;
  if (node.scale.size() == 3) {
    Mat4 s = identity4;
    s[0] = node.scale[0], s[5] = node.scale[1], s[10] = node.scale[2];
    m = s;
  }
  if (node.rotation.size() == 4) {
    const double x = node.rotation[0], y = node.rotation[1], z = node.rotation[2],
                 w = node.rotation[3];
    const Mat4 r = {1 - 2 * (y * y + z * z),
                    2 * (x * y + z * w),
                    2 * (x * z - y * w),
                    0,
                    2 * (x * y - z * w),
                    1 - 2 * (x * x + z * z),
                    2 * (y * z + x * w),
                    0,
                    2 * (x * z + y * w),
                    2 * (y * z - x * w),
                    1 - 2 * (x * x + y * y),
                    0,
                    0,
                    0,
                    0,
                    1};
    m = r * m;
  }
  if (node.translation.size() == 3) {
    Mat4 t = identity4;
    t[12] = node.translation[0], t[13] = node.translation[1], t[14] = node.translation[2];
    m = t * m;
  }
  return m;
}

// Typed, bounds-checked access to the elements of an accessor.
struct AccessorView {
  const unsigned char* data = nullptr;
  std::size_t stride = 0, count = 0, component_size = 0;
  int component_type = 0;
  bool normalized = false;

  double get(std::size_t i, int c) const {
    const unsigned char* p = data + i * stride + c * component_size;
    const auto load = [p]<class T>(T) {
      T v;
      std::memcpy(&v, p, sizeof v);  // glTF data is little-endian, as are the supported hosts
      return v;
    };
    switch (component_type) {
      case TINYGLTF_COMPONENT_TYPE_BYTE: {
        const double v = load(std::int8_t{});
        return normalized ? std::max(v / 127.0, -1.0) : v;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
        const double v = load(std::uint8_t{});
        return normalized ? v / 255.0 : v;
      }
      case TINYGLTF_COMPONENT_TYPE_SHORT: {
        const double v = load(std::int16_t{});
        return normalized ? std::max(v / 32767.0, -1.0) : v;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        const double v = load(std::uint16_t{});
        return normalized ? v / 65535.0 : v;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        return load(std::uint32_t{});
      case TINYGLTF_COMPONENT_TYPE_FLOAT:
        return load(float{});
    }
    return 0;
  }
};

class GltfReader {
 public:
  GltfReader(const fs::path& file, const tinygltf::Model& model, Mesh& mesh)
      : file_(file), model_(model), mesh_(mesh), on_path_(model.nodes.size(), false) {}

  void add_node(int index, const Mat4& parent) {
    if (index < 0 || static_cast<std::size_t>(index) >= model_.nodes.size())
      fail(file_, fmt::format("node {} does not exist", index));
    if (on_path_[index]) fail(file_, fmt::format("node {} is its own ancestor", index));
    on_path_[index] = true;
    const tinygltf::Node& node = model_.nodes[index];
    const Mat4 m = parent * node_transform(node);
    if (node.mesh >= 0) add_mesh(node.mesh, m);
    for (int child : node.children) add_node(child, m);
    on_path_[index] = false;
  }

  void add_mesh(int index, const Mat4& m) {
    if (static_cast<std::size_t>(index) >= model_.meshes.size())
      fail(file_, fmt::format("mesh {} does not exist", index));
    const auto& primitives = model_.meshes[index].primitives;
    for (std::size_t p = 0; p < primitives.size(); ++p) add_primitive(index, p, m);
  }

  bool any_uv() const { return any_uv_; }

 private:
  [[noreturn]] void fail_in(std::string_view what) const {
    fail(file_, fmt::format("mesh {} primitive {}: {}", mesh_index_, primitive_index_, what));
  }

  AccessorView view(int index, const char* what) const {
    if (index < 0 || static_cast<std::size_t>(index) >= model_.accessors.size())
      fail_in(fmt::format("{} accessor {} does not exist", what, index));
    const tinygltf::Accessor& a = model_.accessors[index];
    if (a.sparse.isSparse) fail_in(fmt::format("{} uses a sparse accessor (not supported)", what));
    if (a.bufferView < 0 || static_cast<std::size_t>(a.bufferView) >= model_.bufferViews.size())
      fail_in(fmt::format("{} accessor has no buffer view", what));
    const tinygltf::BufferView& bv = model_.bufferViews[a.bufferView];
    if (bv.buffer < 0 || static_cast<std::size_t>(bv.buffer) >= model_.buffers.size())
      fail_in(fmt::format("{} buffer view has no buffer", what));
    const std::vector<unsigned char>& buffer = model_.buffers[bv.buffer].data;
    AccessorView v;
    v.component_type = a.componentType;
    v.normalized = a.normalized;
    v.count = a.count;
    const int component_size = tinygltf::GetComponentSizeInBytes(a.componentType);
    const int components = tinygltf::GetNumComponentsInType(a.type);
    if (component_size <= 0 || components <= 0)
      fail_in(fmt::format("{} accessor has an invalid type", what));
    v.component_size = component_size;
    const std::size_t element_size = std::size_t(component_size) * components;
    v.stride = bv.byteStride > 0 ? bv.byteStride : element_size;
    if (v.stride < element_size) fail_in(fmt::format("{} buffer view stride is too small", what));
    // Every sum and product checked against the bytes present: declared offsets, lengths and
    // counts come from the file and may be anything up to 2^64.
    const std::size_t size = buffer.size();
    if (bv.byteOffset > size || bv.byteLength > size - bv.byteOffset ||
        a.byteOffset > bv.byteLength)
      fail_in(fmt::format("{} accessor reaches beyond its buffer", what));
    const std::size_t available = bv.byteLength - a.byteOffset;
    if (v.count > 0 &&
        (available < element_size || v.count - 1 > (available - element_size) / v.stride))
      fail_in(fmt::format("{} accessor reaches beyond its buffer", what));
    v.data = buffer.data() + bv.byteOffset + a.byteOffset;
    return v;
  }

  void add_primitive(int mesh_index, std::size_t primitive_index, const Mat4& m) {
    mesh_index_ = mesh_index;
    primitive_index_ = primitive_index;
    const tinygltf::Primitive& prim = model_.meshes[mesh_index].primitives[primitive_index];
    const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    // Points and lines have no surface to render.
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN)
      return;
    const auto position_it = prim.attributes.find("POSITION");
    if (position_it == prim.attributes.end()) fail_in("no POSITION attribute");
    const AccessorView positions = view(position_it->second, "POSITION");
    const tinygltf::Accessor& pa = model_.accessors[position_it->second];
    if (pa.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || pa.type != TINYGLTF_TYPE_VEC3)
      fail_in("POSITION must be a float VEC3 accessor");

    std::optional<AccessorView> texcoords;
    if (const auto it = prim.attributes.find("TEXCOORD_0"); it != prim.attributes.end()) {
      texcoords = view(it->second, "TEXCOORD_0");
      const tinygltf::Accessor& ta = model_.accessors[it->second];
      const bool ok_type =
          ta.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT ||
          (ta.normalized && (ta.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                             ta.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT));
      if (ta.type != TINYGLTF_TYPE_VEC2 || !ok_type)
        fail_in("TEXCOORD_0 must be a VEC2 of floats or normalized unsigned bytes or shorts");
      if (texcoords->count != positions.count)
        fail_in("TEXCOORD_0 and POSITION have different counts");
    }

    const std::size_t base = mesh_.positions.size();
    if (base + positions.count > std::numeric_limits<std::uint32_t>::max())
      fail_in("too many vertices");
    if (texcoords && !any_uv_) {
      mesh_.uvs.assign(base, {0, 0});
      any_uv_ = true;
    }
    for (std::size_t i = 0; i < positions.count; ++i) {
      const Vec3 local{positions.get(i, 0), positions.get(i, 1), positions.get(i, 2)};
      const Vec3 p = transform_point(m, local);
      if (!finite(local) || !finite(p))
        fail_in(fmt::format("vertex {} has a non-finite coordinate", i));
      mesh_.positions.push_back(p);
      if (texcoords) {
        const float u = static_cast<float>(texcoords->get(i, 0));
        const float v = static_cast<float>(texcoords->get(i, 1));
        if (!std::isfinite(u) || !std::isfinite(v))
          fail_in(fmt::format("vertex {} has a non-finite texture coordinate", i));
        mesh_.uvs.push_back({u, v});
      } else if (any_uv_) {
        mesh_.uvs.push_back({0, 0});
      }
    }

    std::vector<std::uint32_t> indices;
    if (prim.indices >= 0) {
      const AccessorView iv = view(prim.indices, "index");
      const tinygltf::Accessor& ia = model_.accessors[prim.indices];
      if (ia.type != TINYGLTF_TYPE_SCALAR ||
          (ia.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
           ia.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
           ia.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
        fail_in("indices must be unsigned byte, short or int scalars");
      indices.reserve(iv.count);
      for (std::size_t i = 0; i < iv.count; ++i) {
        const double index = iv.get(i, 0);
        if (index >= static_cast<double>(positions.count))
          fail_in(fmt::format("index {} out of range ({} vertices)", index, positions.count));
        indices.push_back(static_cast<std::uint32_t>(index));
      }
    } else {
      indices.resize(positions.count);
      for (std::size_t i = 0; i < indices.size(); ++i) indices[i] = static_cast<std::uint32_t>(i);
    }

    // A mirroring transform turns the winding; undo that so front faces stay front faces.
    const bool flip = determinant3(m) < 0;
    const auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
      const auto offset = static_cast<std::uint32_t>(base);
      if (flip) std::swap(b, c);
      mesh_.triangles.push_back({offset + a, offset + b, offset + c});
    };
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      for (std::size_t i = 0; i + 2 < indices.size(); i += 3)
        add(indices[i], indices[i + 1], indices[i + 2]);
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      for (std::size_t i = 0; i + 2 < indices.size(); ++i)
        if (i % 2 == 0)
          add(indices[i], indices[i + 1], indices[i + 2]);
        else
          add(indices[i + 1], indices[i], indices[i + 2]);
    } else {
      for (std::size_t i = 1; i + 1 < indices.size(); ++i)
        add(indices[0], indices[i], indices[i + 1]);
    }
  }

  const fs::path& file_;
  const tinygltf::Model& model_;
  Mesh& mesh_;
  std::vector<bool> on_path_;
  bool any_uv_ = false;
  int mesh_index_ = 0;
  std::size_t primitive_index_ = 0;
};

// Textures are not needed for the geometry: skip decoding them.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int,
                const unsigned char*, int, void*) {
  return true;
}

// tinygltf's messages can quote a whole data URI: keep them to one readable line.
std::string one_line(std::string_view text) {
  constexpr std::size_t max_line = 160;
  std::string out;
  for_each_line(text, [&](std::size_t, std::string_view s) {
    s = trim(s);
    if (s.empty()) return true;
    if (!out.empty()) out += "; ";
    out += s.size() > max_line ? std::string(s.substr(0, max_line)) + "..." : std::string(s);
    return true;
  });
  return out;
}

// The files a glTF names (buffer and image uris). tinygltf joins its base folder and the decoded
// uri and asks the callbacks below whether that path exists and for its bytes, so every file it
// would open passes through read(): each is resolved beneath the mesh file's folder (unless
// the options allow more) and read as the mesh file itself is. The first refusal is kept, to be
// reported for the mesh file whatever tinygltf makes of the failed read (a failed image is only
// a warning to it).
class GltfReferences {
 public:
  GltfReferences(const fs::path& file, const MeshLoadOptions& options)
      : allow_outside_(options.allow_outside) {
    std::error_code ec;
    const fs::path folder = fs::absolute(file, ec).parent_path();
    folder_ = fs::canonical(folder, ec);
    if (ec) folder_ = folder.lexically_normal();
    base_dir_ = folder_.string();
    // The path tinygltf gives the callbacks: base, "/" unless the base ends in one, uri.
    prefix_ = !base_dir_.empty() && base_dir_.back() == '/' ? base_dir_ : base_dir_ + "/";
  }

  const std::string& base_dir() const { return base_dir_; }
  const std::optional<std::string>& refusal() const { return refusal_; }

  tinygltf::FsCallbacks callbacks() {
    tinygltf::FsCallbacks fs{};
    fs.FileExists = &exists;
    fs.ExpandFilePath = &expand;
    fs.ReadWholeFile = &read;
    fs.WriteWholeFile = &write;
    fs.user_data = this;
    return fs;
  }

 private:
  // Every path under the base "exists": read() then decides, the same way whether or not the
  // file is there. (tinygltf would next try the uri against the working folder: never reached.)
  static bool exists(const std::string& path, void* self) {
    return path.starts_with(static_cast<GltfReferences*>(self)->prefix_);
  }

  // No expansion (of `~` or variables): a uri is a path.
  static std::string expand(const std::string& path, void*) { return path; }

  static bool write(std::string* err, const std::string&, const std::vector<unsigned char>&,
                    void*) {
    if (err) *err += "writing is not supported";
    return false;
  }

  static bool read(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                   void* self) {
    return static_cast<GltfReferences*>(self)->read(*out, err, path);
  }

  bool read(std::vector<unsigned char>& out, std::string* err, const std::string& path) {
    if (!path.starts_with(prefix_)) return refuse(path, "it is not under the glTF's folder", err);
    const std::string uri = path.substr(prefix_.size());
    if (uri.find('\0') != std::string::npos) return refuse(uri, "it contains a NUL byte", err);
    std::string reason;
    const std::optional<fs::path> target = resolve(uri, reason);
    if (!target) return refuse(uri, reason, err);
    std::error_code ec;
    if (!fs::exists(fs::symlink_status(*target, ec))) {
      // A missing file is tinygltf's to report (an error for a buffer, a warning for an image).
      if (err) *err += "no such file";
      return false;
    }
    std::optional<std::string> bytes = try_read_input_file(*target, kMaxAssetFileBytes, reason);
    if (!bytes) return refuse(uri, reason, err);
    out.assign(bytes->begin(), bytes->end());
    return true;
  }

  bool refuse(const std::string& uri, const std::string& reason, std::string* err) {
    constexpr std::size_t max_uri = 160;
    const std::string shown = uri.size() > max_uri ? uri.substr(0, max_uri) + "..." : uri;
    std::string message = fmt::format("uri {:?}: {}", shown, reason);
    if (err) *err += message;
    if (!refusal_) refusal_ = std::move(message);
    return false;
  }

  // The file `uri` names, or nullopt with `reason`. Unless outside files are allowed, the uri is
  // resolved beneath the folder step by step, as the system would resolve it, and refused at
  // the first step that leaves the folder: an absolute uri, a `..` above the folder, a symbolic
  // link whose target leads out. Only paths inside the folder are ever looked at, so the answer
  // for a uri that leads out is the same whether or not a file lies where it leads.
  std::optional<fs::path> resolve(const std::string& uri, std::string& reason) const {
    const fs::path given(uri);
    if (allow_outside_) return given.is_absolute() ? given : folder_ / given;
    const auto outside = [&]() -> std::optional<fs::path> {
      reason = "it is outside the mesh file's folder (allow that with --allow-outside)";
      return std::nullopt;
    };
    if (given.has_root_path()) return outside();
    std::vector<fs::path> todo;  // the steps still to take, the next one last
    const auto push = [&](const fs::path& p) {
      const std::size_t at = todo.size();
      for (const fs::path& step : p) todo.push_back(step);
      std::reverse(todo.begin() + static_cast<std::ptrdiff_t>(at), todo.end());
    };
    push(given);
    fs::path current = folder_;
    std::size_t depth = 0;  // steps below the folder
    int links = 0;
    while (!todo.empty()) {
      const fs::path step = std::move(todo.back());
      todo.pop_back();
      if (step.empty() || step == ".") continue;
      if (step == "..") {
        if (depth == 0) return outside();
        current = current.parent_path();
        --depth;
        continue;
      }
      const fs::path next = current / step;
      std::error_code ec;
      if (!fs::is_symlink(fs::symlink_status(next, ec))) {
        current = next;
        ++depth;
        continue;
      }
      if (++links > 40) {
        reason = "too many levels of symbolic links";
        return std::nullopt;
      }
      const fs::path target = fs::read_symlink(next, ec);
      if (ec) {
        reason = ec.message();
        return std::nullopt;
      }
      if (target.has_root_path()) {
        // Inside only if it names a place in the folder as written (the folder is canonical).
        const fs::path within = target.lexically_normal().lexically_relative(folder_);
        if (within.empty() || *within.begin() == "..") return outside();
        current = folder_;
        depth = 0;
        push(within);
      } else {
        push(target);  // from the link's own folder, `current`
      }
    }
    return current;
  }

  bool allow_outside_ = false;
  fs::path folder_;  // canonical
  std::string base_dir_, prefix_;
  std::optional<std::string> refusal_;
};

std::shared_ptr<Mesh> load_gltf(const fs::path& file, bool binary, MeshLoadReport& report,
                                const MeshLoadOptions& options) {
  const std::string data = read_whole_file(file);
  if (data.size() > std::numeric_limits<unsigned int>::max()) fail(file, "file too large");
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(skip_image, nullptr);
  GltfReferences references(file, options);
  loader.SetFsCallbacks(references.callbacks());
  tinygltf::Model model;
  std::string err, warn;
  const std::string& base_dir = references.base_dir();
  const bool ok =
      binary ? loader.LoadBinaryFromMemory(&model, &err, &warn,
                                           reinterpret_cast<const unsigned char*>(data.data()),
                                           static_cast<unsigned int>(data.size()), base_dir)
             : loader.LoadASCIIFromString(&model, &err, &warn, data.data(),
                                          static_cast<unsigned int>(data.size()), base_dir);
  if (references.refusal()) fail(file, *references.refusal());
  if (!ok) fail(file, err.empty() ? "cannot parse glTF file" : one_line(err));

  auto mesh = std::make_shared<Mesh>();
  mesh->source = file.string();
  GltfReader reader(file, model, *mesh);
  if (model.scenes.empty()) {
    for (std::size_t i = 0; i < model.meshes.size(); ++i)
      reader.add_mesh(static_cast<int>(i), identity4);
  } else {
    const int scene = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (static_cast<std::size_t>(scene) >= model.scenes.size())
      fail(file, fmt::format("default scene {} does not exist", scene));
    for (int node : model.scenes[scene].nodes) reader.add_node(node, identity4);
  }
  if (!reader.any_uv()) mesh->uvs.clear();
  return finish_mesh(std::move(mesh), file, report);
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

std::shared_ptr<Mesh> load_mesh_file(const std::filesystem::path& file, MeshLoadReport& report,
                                     const MeshLoadOptions& options) {
  report = {};
  const std::string ext = lower(file.extension().string());
  if (ext == ".obj") return load_obj(file, report);
  if (ext == ".ply") return load_ply(file, report);
  if (ext == ".gltf") return load_gltf(file, false, report, options);
  if (ext == ".glb") return load_gltf(file, true, report, options);
  fail(file, fmt::format("unsupported mesh format '{}' (use .obj, .ply, .gltf or .glb)", ext));
}

}  // namespace lightcone
