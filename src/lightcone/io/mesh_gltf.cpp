// glTF 2.0 meshes (.gltf, .glb) through tinygltf: the default scene's nodes with their
// transforms; every file a glTF names read through GltfReferences (regular files only, inside
// the mesh file's folder unless allowed).
#include <fmt/format.h>
#include <tiny_gltf.h>

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
#include "lightcone/io/input_file.hpp"
#include "lightcone/io/mesh_file.hpp"
#include "lightcone/io/mesh_reading.hpp"

namespace lightcone::mesh_io {

namespace fs = std::filesystem;

namespace {

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
    std::vector<fs::path> steps_left;  // the steps still to take, the next one last
    const auto push = [&](const fs::path& p) {
      const std::size_t at = steps_left.size();
      for (const fs::path& step : p) steps_left.push_back(step);
      std::reverse(steps_left.begin() + static_cast<std::ptrdiff_t>(at), steps_left.end());
    };
    push(given);
    fs::path current = folder_;
    std::size_t depth = 0;  // steps below the folder
    int links = 0;
    while (!steps_left.empty()) {
      const fs::path step = std::move(steps_left.back());
      steps_left.pop_back();
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

}  // namespace

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

}  // namespace lightcone::mesh_io
