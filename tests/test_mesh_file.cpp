// Mesh loading: OBJ, PLY (ASCII, binary both byte orders) and glTF (.gltf, .glb) files written
// into a temporary directory, and the error messages for broken ones.
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <bit>
#include <cstring>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "lightcone/io/input_error.hpp"
#include "lightcone/io/mesh_file.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;
using test::base64;

using MeshFileTest = test::TempDirTest;

// The InputError message of `f`, or "" when it throws nothing.
std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string load_error(const fs::path& path) {
  return error_of([&] {
    MeshLoadReport report;
    load_mesh_file(path, report);
  });
}

std::shared_ptr<Mesh> load(const fs::path& path, std::size_t expected_dropped = 0) {
  MeshLoadReport report;
  auto mesh = load_mesh_file(path, report);
  EXPECT_EQ(report.degenerate_triangles_dropped, expected_dropped);
  EXPECT_EQ(mesh->source, path.string());
  return mesh;
}

void expect_same_mesh(const Mesh& a, const Mesh& b) {
  ASSERT_EQ(a.positions.size(), b.positions.size());
  for (std::size_t i = 0; i < a.positions.size(); ++i) {
    EXPECT_DOUBLE_EQ(a.positions[i].x, b.positions[i].x) << i;
    EXPECT_DOUBLE_EQ(a.positions[i].y, b.positions[i].y) << i;
    EXPECT_DOUBLE_EQ(a.positions[i].z, b.positions[i].z) << i;
  }
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.uvs, b.uvs);
}

// ----------------------------------------------------------------------------------------------
// OBJ

TEST_F(MeshFileTest, ObjQuadBecomesTwoTriangles) {
  const auto path = write("quad.obj",
                          "# a unit quad\n"
                          "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                          "f 1 2 3 4\n");
  const auto mesh = load(path);
  ASSERT_EQ(mesh->positions.size(), 4u);
  EXPECT_EQ(mesh->positions[2].x, 1);
  EXPECT_EQ(mesh->positions[2].y, 1);
  ASSERT_EQ(mesh->triangles.size(), 2u);
  EXPECT_TRUE(mesh->uvs.empty());
  for (const auto& t : mesh->triangles)
    for (auto i : t) EXPECT_LT(i, 4u);
}

TEST_F(MeshFileTest, ObjTexcoordsBuildPositionTexcoordPairs) {
  // Position 1 is used with two different texcoords, so it becomes two vertices.
  const auto path = write("uv.obj",
                          "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                          "vt 0 0\nvt 1 0\nvt 1 1\nvt 0.5 0.5\nvt 0 1\n"
                          "f 1/1 2/2 3/3\n"
                          "f 1/4 3/3 4/5\n");
  const auto mesh = load(path);
  ASSERT_EQ(mesh->positions.size(), 5u);
  ASSERT_EQ(mesh->uvs.size(), 5u);
  ASSERT_EQ(mesh->triangles.size(), 2u);
  const auto& t = mesh->triangles[1];
  EXPECT_EQ(mesh->positions[t[0]].x, 0);
  EXPECT_EQ(mesh->positions[t[0]].y, 0);
  EXPECT_EQ(mesh->uvs[t[0]], (std::array<float, 2>{0.5f, 0.5f}));
  EXPECT_EQ(mesh->positions[t[2]].y, 1);
  EXPECT_EQ(mesh->positions[t[2]].x, 0);
  // Stored in image order: v = 1 - the file's v.
  EXPECT_EQ(mesh->uvs[t[2]], (std::array<float, 2>{0, 0}));
  // The shared (position 3, texcoord 3) pair is one vertex.
  EXPECT_EQ(mesh->triangles[0][2], t[1]);
  EXPECT_EQ(mesh->uvs[t[1]], (std::array<float, 2>{1, 0}));
}

TEST_F(MeshFileTest, ObjNegativeIndicesCountBack) {
  const auto mesh = load(write("neg.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n"));
  ASSERT_EQ(mesh->triangles.size(), 1u);
  EXPECT_EQ(mesh->triangles[0], (std::array<std::uint32_t, 3>{0, 1, 2}));
}

TEST_F(MeshFileTest, ObjDegenerateTrianglesAreDroppedAndCounted) {
  const auto path = write("degenerate.obj",
                          "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\n"
                          "f 1 2 3 4\n"
                          "f 1 1 2\n"    // repeated index
                          "f 1 2 5\n");  // collinear: zero area
  const auto mesh = load(path, 2);
  EXPECT_EQ(mesh->triangles.size(), 2u);
}

TEST_F(MeshFileTest, ObjOutOfRangeIndexNamesTheLine) {
  const auto path = write("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 9\n");
  EXPECT_EQ(load_error(path), path.string() + ":5: vertex index 9 out of range (3 vertices)");
  // tinyobjloader silently skips a bad quad; it must still be reported.
  const auto quad = write("quad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 3 7\n");
  EXPECT_EQ(load_error(quad), quad.string() + ":5: vertex index 7 out of range (3 vertices)");
  const auto texcoord = write("vt.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/2\n");
  EXPECT_EQ(load_error(texcoord),
            texcoord.string() + ":5: texcoord index 2 out of range (1 texcoords)");
  const auto zero = write("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
  EXPECT_EQ(load_error(zero), zero.string() + ":4: invalid face: zero or malformed vertex index");
}

TEST_F(MeshFileTest, ObjNonFiniteCoordinateNamesTheLine) {
  const auto path = write("inf.obj", "v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_EQ(load_error(path), path.string() + ":2: non-finite vertex coordinate");
}

TEST_F(MeshFileTest, MissingAndEmptyFiles) {
  const fs::path missing = dir_ / "missing.obj";
  EXPECT_EQ(load_error(missing),
            missing.string() + ": cannot read mesh file: No such file or directory");
  const auto empty = write("empty.obj", "");
  EXPECT_EQ(load_error(empty), empty.string() + ": mesh has no triangles");
  const auto only_degenerate = write("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  EXPECT_EQ(load_error(only_degenerate),
            only_degenerate.string() + ": mesh has no triangles (all 1 are degenerate)");
}

TEST_F(MeshFileTest, UnknownExtension) {
  const auto path = write("mesh.xyz", "whatever");
  EXPECT_EQ(load_error(path),
            path.string() + ": unsupported mesh format '.xyz' (use .obj, .ply, .gltf or .glb)");
}

// ----------------------------------------------------------------------------------------------
// PLY

struct Cube {
  std::vector<std::array<float, 3>> positions;
  std::vector<std::array<float, 2>> uvs;
  std::vector<std::vector<int>> faces;
};

Cube cube() {
  Cube c;
  for (int i = 0; i < 8; ++i) {
    c.positions.push_back({float(i & 1), float((i >> 1) & 1), float((i >> 2) & 1)});
    c.uvs.push_back({0.125f * i, 1 - 0.125f * i});
  }
  c.faces = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  return c;
}

// Vertices carry an extra property and faces an extra list, and an extra element follows, all of
// which the reader must skip.
std::string ply_header(const char* format, bool uv) {
  std::string h = "ply\nformat " + std::string(format) +
                  " 1.0\ncomment written by the test\nelement vertex 8\n"
                  "property float x\nproperty float y\nproperty double z\n";
  if (uv) h += "property float s\nproperty float t\n";
  h += "property uchar red\n"
       "element face 6\nproperty list uchar int vertex_indices\n"
       "property list uchar float extra\n"
       "element edge 1\nproperty int vertex1\nproperty int vertex2\n"
       "end_header\n";
  return h;
}

std::string ascii_ply(const Cube& c, bool uv) {
  std::string s = ply_header("ascii", uv);
  for (std::size_t i = 0; i < c.positions.size(); ++i) {
    const auto& p = c.positions[i];
    s += fmt::format("{} {} {}", p[0], p[1], p[2]);
    if (uv) s += fmt::format(" {} {}", c.uvs[i][0], c.uvs[i][1]);
    s += " 200\n";
  }
  for (const auto& f : c.faces) s += fmt::format("{} {} 2 0.5 0.25\n", f.size(), fmt::join(f, " "));
  return s + "0 1\n";
}

template <class T>
void put(std::string& s, T value, bool big_endian) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if (big_endian != (std::endian::native == std::endian::big))
    std::reverse(bytes, bytes + sizeof(T));
  s.append(bytes, sizeof(T));
}

std::string binary_ply(const Cube& c, bool uv, bool big_endian) {
  std::string s = ply_header(big_endian ? "binary_big_endian" : "binary_little_endian", uv);
  for (std::size_t i = 0; i < c.positions.size(); ++i) {
    const auto& p = c.positions[i];
    put(s, p[0], big_endian);
    put(s, p[1], big_endian);
    put(s, double(p[2]), big_endian);
    if (uv) {
      put(s, c.uvs[i][0], big_endian);
      put(s, c.uvs[i][1], big_endian);
    }
    put(s, std::uint8_t{200}, big_endian);
  }
  for (const auto& f : c.faces) {
    put(s, static_cast<std::uint8_t>(f.size()), big_endian);
    for (int i : f) put(s, std::int32_t(i), big_endian);
    put(s, std::uint8_t{2}, big_endian);
    put(s, 0.5f, big_endian);
    put(s, 0.25f, big_endian);
  }
  put(s, std::int32_t{0}, big_endian);
  put(s, std::int32_t{1}, big_endian);
  return s;
}

TEST_F(MeshFileTest, PlyAsciiAndBinaryGiveTheSameCube) {
  const Cube c = cube();
  for (bool uv : {false, true}) {
    SCOPED_TRACE(uv ? "with uv" : "without uv");
    const auto ascii = load(write("ascii.ply", ascii_ply(c, uv)));
    const auto little = load(write("little.ply", binary_ply(c, uv, false)));
    const auto big = load(write("big.ply", binary_ply(c, uv, true)));
    ASSERT_EQ(ascii->positions.size(), 8u);
    ASSERT_EQ(ascii->triangles.size(), 12u);
    EXPECT_EQ(ascii->uvs.size(), uv ? 8u : 0u);
    if (uv) {
      EXPECT_EQ(ascii->uvs[3], (std::array<float, 2>{c.uvs[3][0], 1 - c.uvs[3][1]}));
    }
    EXPECT_EQ(ascii->positions[5].x, 1);
    EXPECT_EQ(ascii->positions[5].z, 1);
    // Fan triangulation of the first face (0 2 3 1).
    EXPECT_EQ(ascii->triangles[0], (std::array<std::uint32_t, 3>{0, 2, 3}));
    EXPECT_EQ(ascii->triangles[1], (std::array<std::uint32_t, 3>{0, 3, 1}));
    expect_same_mesh(*ascii, *little);
    expect_same_mesh(*ascii, *big);
  }
}

TEST_F(MeshFileTest, PlyTruncatedBinaryFails) {
  std::string data = binary_ply(cube(), true, false);
  data.resize(data.size() - 40);
  const auto path = write("truncated.ply", data);
  EXPECT_EQ(load_error(path),
            path.string() + ": unexpected end of file: 4 of 6 'face' elements read");
}

TEST_F(MeshFileTest, PlyBadHeaderNamesTheLine) {
  std::string data = ascii_ply(cube(), false);
  data.replace(data.find("property double z"), 17, "property doubel z");
  const auto path = write("header.ply", data);
  EXPECT_EQ(load_error(path), path.string() + ":7: unknown property type 'doubel'");

  const auto not_ply = write("not.ply", "plx\n");
  EXPECT_EQ(load_error(not_ply),
            not_ply.string() + ":1: not a PLY file (the first line must be 'ply')");

  const auto no_z = write("noz.ply",
                          "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\n"
                          "property float y\nend_header\n");
  EXPECT_EQ(load_error(no_z), no_z.string() + ":3: element 'vertex' has no scalar property 'z'");
}

TEST_F(MeshFileTest, PlyAsciiBodyErrorsNameTheLine) {
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar uint vertex_index\nend_header\n";
  const auto range = write("range.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n");
  EXPECT_EQ(load_error(range), range.string() + ":13: vertex index 3 out of range (3 vertices)");
  const auto few = write("few.ply", header + "0 0 0\n1 0\n0 1 0\n3 0 1 2\n");
  EXPECT_EQ(load_error(few), few.string() + ":11: too few values for element 'vertex'");
  const auto nan = write("nan.ply", header + "0 0 0\n1 0 0\nnan 1 0\n3 0 1 2\n");
  EXPECT_EQ(load_error(nan), nan.string() + ":12: non-finite vertex coordinate");
  const auto eof = write("eof.ply", header + "0 0 0\n1 0 0\n0 1 0\n");
  EXPECT_EQ(load_error(eof),
            eof.string() + ":12: unexpected end of file: 0 of 1 'face' elements read");
  const auto ok = load(write("ok.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
  EXPECT_EQ(ok->triangles.size(), 1u);
}

TEST_F(MeshFileTest, PlyBinaryIndexOutOfRange) {
  std::string data = binary_ply(cube(), false, false);
  // Faces are 26 bytes (count, 4 indices, extra list) and the edge 8 bytes at the end; the first
  // index of face 2 follows its count byte.
  const std::size_t face_size = 1 + 4 * 4 + 1 + 2 * 4;
  const std::size_t face2 = data.size() - 8 - 6 * face_size + 2 * face_size + 1;
  const std::int32_t bad = 8;
  std::memcpy(&data[face2], &bad, 4);
  const auto path = write("bad.ply", data);
  EXPECT_EQ(load_error(path), path.string() + ": face 2: vertex index 8 out of range (8 vertices)");
}

// ----------------------------------------------------------------------------------------------
// glTF

// One triangle: float positions, float texcoords and unsigned short indices.
std::string triangle_buffer(std::uint16_t last_index = 2) {
  std::string b;
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) put(b, v, false);
  for (float v : {0.f, 0.f, 1.f, 0.f, 0.f, 1.f}) put(b, v, false);
  for (std::uint16_t i : {std::uint16_t{0}, std::uint16_t{1}, last_index}) put(b, i, false);
  b += std::string(2, '\0');  // pad to a multiple of 4
  return b;
}

// `buffer_uri` empty: the buffer is the GLB's binary chunk.
std::string triangle_gltf(const std::string& buffer_uri, std::size_t buffer_size,
                          const std::string& nodes, const std::string& scene_nodes) {
  const std::string uri = buffer_uri.empty() ? "" : "\"uri\": \"" + buffer_uri + "\", ";
  return R"({"asset": {"version": "2.0"},
  "scene": 0, "scenes": [{"nodes": )" +
         scene_nodes + R"(}], "nodes": )" + nodes + R"(,
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2}]}],
  "buffers": [{)" +
         uri + "\"byteLength\": " + std::to_string(buffer_size) + R"(}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                  {"buffer": 0, "byteOffset": 36, "byteLength": 24},
                  {"buffer": 0, "byteOffset": 60, "byteLength": 6}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
     "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"},
    {"bufferView": 2, "componentType": 5123, "count": 3, "type": "SCALAR"}]})";
}

std::string glb(std::string json, const std::string& bin) {
  json.append((4 - json.size() % 4) % 4, ' ');
  std::string out;
  put(out, std::uint32_t{0x46546C67}, false);  // "glTF"
  put(out, std::uint32_t{2}, false);
  put(out, std::uint32_t(12 + 8 + json.size() + 8 + bin.size()), false);
  put(out, std::uint32_t(json.size()), false);
  put(out, std::uint32_t{0x4E4F534A}, false);  // "JSON"
  out += json;
  put(out, std::uint32_t(bin.size()), false);
  put(out, std::uint32_t{0x004E4942}, false);  // "BIN\0"
  return out + bin;
}

const std::string translated_node = R"([{"mesh": 0, "translation": [10, 20, 30]}])";

void expect_translated_triangle(const Mesh& mesh) {
  ASSERT_EQ(mesh.positions.size(), 3u);
  ASSERT_EQ(mesh.triangles.size(), 1u);
  EXPECT_EQ(mesh.positions[1].x, 11);
  EXPECT_EQ(mesh.positions[1].y, 20);
  EXPECT_EQ(mesh.positions[1].z, 30);
  EXPECT_EQ(mesh.positions[2].y, 21);
  // glTF's texture coordinates are already in image order (v down), as the mesh stores them.
  ASSERT_EQ(mesh.uvs.size(), 3u);
  EXPECT_EQ(mesh.uvs[0], (std::array<float, 2>{0, 0}));
  EXPECT_EQ(mesh.uvs[2], (std::array<float, 2>{0, 1}));
}

TEST_F(MeshFileTest, GltfWithDataUriAppliesNodeTranslation) {
  const std::string buffer = triangle_buffer();
  const auto path =
      write("triangle.gltf", triangle_gltf("data:application/octet-stream;base64," + base64(buffer),
                                           buffer.size(), translated_node, "[0]"));
  expect_translated_triangle(*load(path));
}

TEST_F(MeshFileTest, GlbGivesTheSameTriangle) {
  const std::string buffer = triangle_buffer();
  const auto path =
      write("triangle.glb", glb(triangle_gltf("", buffer.size(), translated_node, "[0]"), buffer));
  expect_translated_triangle(*load(path));
}

TEST_F(MeshFileTest, GltfNodeHierarchyComposesTransforms) {
  // Parent scales by 2 and rotates 90 degrees about z; the child translates by (1, 0, 0).
  const std::string nodes = R"([{"children": [1], "scale": [2, 2, 2],
                                 "rotation": [0, 0, 0.7071067811865476, 0.7071067811865476]},
                                {"mesh": 0, "translation": [1, 0, 0]}])";
  const std::string buffer = triangle_buffer();
  const auto path =
      write("tree.gltf", triangle_gltf("data:application/octet-stream;base64," + base64(buffer),
                                       buffer.size(), nodes, "[0]"));
  const auto mesh = load(path);
  ASSERT_EQ(mesh->positions.size(), 3u);
  // (1, 0, 0) + (1, 0, 0) = (2, 0, 0), rotated to (0, 2, 0), scaled to (0, 4, 0).
  EXPECT_NEAR(mesh->positions[1].x, 0, 1e-12);
  EXPECT_NEAR(mesh->positions[1].y, 4, 1e-12);
  EXPECT_NEAR(mesh->positions[0].y, 2, 1e-12);
}

TEST_F(MeshFileTest, GltfIndexOutOfRange) {
  const std::string buffer = triangle_buffer(5);
  const auto path =
      write("bad.glb", glb(triangle_gltf("", buffer.size(), translated_node, "[0]"), buffer));
  EXPECT_EQ(load_error(path),
            path.string() + ": mesh 0 primitive 0: index 5 out of range (3 vertices)");
}

// Declared offsets, lengths and counts near 2^64 must not wrap past the bounds checks.
TEST_F(MeshFileTest, GltfHugeOffsetsAndCountsAreErrorsNotCrashes) {
  const std::string buffer = triangle_buffer();
  const std::string good = triangle_gltf("", buffer.size(), translated_node, "[0]");
  const struct {
    const char* from;
    const char* to;
  } cases[] = {
      {R"("byteOffset": 0, "byteLength": 36})",
       R"("byteOffset": 9223372036854775808, "byteLength": 9223372036854775832})"},
      {R"("byteOffset": 0, "byteLength": 36})",
       R"("byteOffset": 18446744073709551608, "byteLength": 36})"},
      {R"("componentType": 5123, "count": 3,)",
       R"("componentType": 5123, "count": 4611686018427387905,)"},
      {R"("componentType": 5126, "count": 3, "type": "VEC3")",
       R"("componentType": 5126, "count": 18446744073709551615, "type": "VEC3")"},
  };
  for (const auto& c : cases) {
    std::string json = good;
    const std::size_t at = json.find(c.from);
    ASSERT_NE(at, std::string::npos) << c.from;
    json.replace(at, std::string(c.from).size(), c.to);
    const auto path = write("huge.glb", glb(json, buffer));
    const std::string error = load_error(path);
    EXPECT_EQ(error.rfind(path.string() + ": ", 0), 0u) << c.to << ": " << error;
  }
}

TEST_F(MeshFileTest, PlyDeclaringBillionsOfVerticesFailsAtTheEndOfItsData) {
  const auto path = write("huge.ply",
                          "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\n"
                          "property float x\nproperty float y\nproperty float z\nend_header\n" +
                              std::string(24, '\0'));
  const std::string error = load_error(path);
  EXPECT_EQ(error.rfind(path.string() + ": ", 0), 0u) << error;
}

TEST_F(MeshFileTest, GltfGarbageFails) {
  const auto path = write("garbage.gltf", "{ not json");
  const std::string error = load_error(path);
  EXPECT_EQ(error.rfind(path.string() + ": ", 0), 0u) << error;
}

// ----------------------------------------------------------------------------------------------
// The example assets written by assets/make_meshes.py

TEST(RepositoryMeshes, IcosphereObjAndPlyAgree) {
  const fs::path dir = fs::path(LIGHTCONE_SOURCE_DIR) / "assets" / "meshes";
  const auto obj = load(dir / "icosphere.obj");
  const auto ply = load(dir / "icosphere.ply");
  ASSERT_EQ(obj->triangles.size(), 1280u);
  // Both files list the (position, texcoord) pairs in the same first-use order.
  EXPECT_EQ(obj->triangles, ply->triangles);
  ASSERT_EQ(obj->positions.size(), ply->positions.size());
  ASSERT_EQ(obj->uvs.size(), obj->positions.size());
  ASSERT_EQ(ply->uvs.size(), ply->positions.size());
  for (std::size_t i = 0; i < obj->positions.size(); ++i) {
    EXPECT_NEAR(length(obj->positions[i]), 1, 1e-5);
    EXPECT_NEAR(length(obj->positions[i] - ply->positions[i]), 0, 1e-6);
    EXPECT_NEAR(obj->uvs[i][0], ply->uvs[i][0], 1e-6);
    EXPECT_NEAR(obj->uvs[i][1], ply->uvs[i][1], 1e-6);
  }
}

TEST(RepositoryMeshes, TowerGltfLoads) {
  const auto tower = load(fs::path(LIGHTCONE_SOURCE_DIR) / "assets" / "meshes" / "tower.gltf");
  EXPECT_EQ(tower->triangles.size(), 36u);
  EXPECT_EQ(tower->uvs.size(), tower->positions.size());
  double top = 0;
  for (const Vec3& p : tower->positions) top = std::max(top, p.y);
  EXPECT_DOUBLE_EQ(top, 9.0);
}

}  // namespace
}  // namespace lightcone
