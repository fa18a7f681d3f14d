// PLY meshes (ASCII and binary, either byte order) through a compact reader: Debian packages no
// PLY library. v is stored as 1 - v (image order).
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <bit>
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
  [[noreturn]] void fail_plain(std::string_view what) const { mesh_io::fail(file_, what); }

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

}  // namespace

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

}  // namespace lightcone::mesh_io
