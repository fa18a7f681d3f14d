// The files a mesh file names (a glTF's buffer and image uris, an OBJ's mtllib): read as the
// mesh file itself is (regular files only, within the size limit), only inside the mesh file's
// own folder unless --allow-outside (MeshLoadOptions::allow_outside) says otherwise, and refused
// with a message that says nothing of the files outside the folder.
//
// Each test lays out its folder as
//   meshes/           the mesh file's folder (tri.gltf, tri.bin, sub/tri.bin)
//   outside/          a folder beside it (secret.bin, a valid buffer that must not be read)
//   scene.json        a scene with one object, the mesh meshes/tri.gltf
// The FIFO cases run the program under `timeout`, so that a regression fails instead of hanging.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <string>

#include "lightcone/io/input_error.hpp"
#include "lightcone/io/mesh_file.hpp"
#include "support/test_support.hpp"

namespace lightcone {
namespace {

namespace fs = std::filesystem;
using test::base64;
using test::quoted;

// ---------------------------------------------------------------------------------------------
// A one-triangle glTF and its buffer

template <class T>
void put(std::string& out, T value) {
  char bytes[sizeof value];
  std::memcpy(bytes, &value, sizeof value);  // the hosts are little-endian, as glTF is
  out.append(bytes, sizeof value);
}

// Float positions, then unsigned short indices (padded to 4 bytes): 44 bytes.
std::string triangle_buffer() {
  std::string b;
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) put(b, v);
  for (std::uint16_t i : {0, 1, 2}) put(b, i);
  b += std::string(2, '\0');
  return b;
}

// `uri` empty: the buffer is a GLB's binary chunk. `images` is the glTF's "images" array.
std::string triangle_gltf(const std::string& uri, const std::string& images = "[]") {
  const std::string uri_member = uri.empty() ? "" : "\"uri\": \"" + uri + "\", ";
  return R"({"asset": {"version": "2.0"},
  "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
  "buffers": [{)" +
         uri_member + "\"byteLength\": " + std::to_string(triangle_buffer().size()) + R"(}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                  {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
     "min": [0, 0, 0], "max": [1, 1, 0]},
    {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
  "images": )" +
         images + "}";
}

std::string glb(std::string json, const std::string& bin) {
  json.append((4 - json.size() % 4) % 4, ' ');
  std::string out;
  put(out, std::uint32_t{0x46546C67});  // "glTF"
  put(out, std::uint32_t{2});
  put(out, std::uint32_t(12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size())));
  put(out, std::uint32_t(json.size()));
  put(out, std::uint32_t{0x4E4F534A});  // "JSON"
  out += json;
  if (bin.empty()) return out;
  put(out, std::uint32_t(bin.size()));
  put(out, std::uint32_t{0x004E4942});  // "BIN\0"
  return out + bin;
}

// A small scene: the mesh in front of the camera.
std::string scene_with_mesh(const std::string& mesh) {
  return R"({
  "camera": {"position": [0.3, 0.3, 3], "fov": 40, "width": 32, "height": 24},
  "objects": [{"name": "tri", "shape": {"mesh": {"file": ")" +
         mesh + R"("}}, "material": {"color": [0, 1, 0]}}],
  "sky": {"color": [0, 0, 1]},
  "render": {"exposure": 0}
})";
}

// ---------------------------------------------------------------------------------------------

class MeshReferencesTest : public test::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    fs::create_directories(dir_ / "meshes" / "sub");
    fs::create_directories(dir_ / "outside");
    write("meshes/tri.bin", triangle_buffer());
    write("meshes/sub/tri.bin", triangle_buffer());
    // A valid buffer of a size no message may show.
    write("outside/secret.bin", triangle_buffer() + std::string(12345 - 44, '\0'));
    write("scene.json", scene_with_mesh("meshes/tri.gltf"));
  }

  fs::path meshes() const { return dir_ / "meshes"; }
  fs::path outside() const { return dir_ / "outside"; }

  fs::path gltf(const std::string& uri, const std::string& images = "[]") const {
    return write("meshes/tri.gltf", triangle_gltf(uri, images));
  }

  // The InputError of loading `file`, or "" when it loads.
  static std::string error_of(const fs::path& file, bool allow_outside = false) {
    try {
      MeshLoadReport report;
      MeshLoadOptions options;
      options.allow_outside = allow_outside;
      const auto mesh = load_mesh_file(file, report, options);
      EXPECT_EQ(mesh->triangles.size(), 1u);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }

  // The message of a reference refused because it leads outside the folder.
  static std::string outside_message(const fs::path& file, const std::string& uri) {
    return fmt::format(
        "{}: uri \"{}\": it is outside the mesh file's folder (allow that with --allow-outside)",
        file.string(), uri);
  }

  // `lightcone ARGS` under `timeout 20`: a hang fails the test (status 124) instead of the suite.
  static test::CommandResult run_limited(const std::string& arguments) {
    return test::run_command(std::string("timeout 20 '") + LIGHTCONE_BINARY + "' " + arguments);
  }

  test::CommandResult render(const std::string& extra = "") const {
    return run_limited("render " + quoted(dir_ / "scene.json") + " -o " + quoted(dir_ / "out.png") +
                       " --quiet " + extra);
  }

  // The refusal of a render: status 2 (bad input), the message, and no image.
  void expect_refused(const test::CommandResult& r, const std::string& message) const {
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "out.png"));
  }
};

// --- Allowed: beside, below, data URIs ---------------------------------------------------------

TEST_F(MeshReferencesTest, BufferBesideTheGltfLoads) {
  EXPECT_EQ(error_of(gltf("tri.bin")), "");
  EXPECT_EQ(error_of(gltf("./tri.bin")), "");
}

TEST_F(MeshReferencesTest, BufferInASubfolderLoads) {
  EXPECT_EQ(error_of(gltf("sub/tri.bin")), "");
  EXPECT_EQ(error_of(gltf("sub/../sub/./tri.bin")), "");
  EXPECT_EQ(error_of(gltf("sub%2Ftri.bin")), "");  // percent-encoded, as uris may be
  EXPECT_EQ(error_of(gltf("sub/..//tri.bin")), "");
}

TEST_F(MeshReferencesTest, DataUriLoads) {
  EXPECT_EQ(error_of(gltf("data:application/octet-stream;base64," + base64(triangle_buffer()))),
            "");
}

TEST_F(MeshReferencesTest, GlbWithItsOwnChunkOrABufferBesideLoads) {
  EXPECT_EQ(error_of(write("meshes/tri.glb", glb(triangle_gltf(""), triangle_buffer()))), "");
  EXPECT_EQ(error_of(write("meshes/tri.glb", glb(triangle_gltf("sub/tri.bin"), ""))), "");
}

TEST_F(MeshReferencesTest, MeshFileNamedThroughDotDotStillReadsItsOwnFolder) {
  // As the bundled scenes name their meshes (../assets/meshes/x.gltf).
  gltf("tri.bin");
  EXPECT_EQ(error_of(dir_ / "outside" / ".." / "meshes" / "tri.gltf"), "");
  const fs::path previous = fs::current_path();
  fs::current_path(meshes());
  EXPECT_EQ(error_of("tri.gltf"), "");  // a bare name: its folder is the working folder
  fs::current_path(previous);
}

TEST_F(MeshReferencesTest, SymbolicLinksThatStayInsideAreFollowed) {
  fs::create_symlink("sub/tri.bin", meshes() / "link.bin");
  fs::create_directory_symlink("sub", meshes() / "linked");
  fs::create_symlink(meshes() / "tri.bin", meshes() / "absolute.bin");  // absolute, inside
  EXPECT_EQ(error_of(gltf("link.bin")), "");
  EXPECT_EQ(error_of(gltf("linked/tri.bin")), "");
  EXPECT_EQ(error_of(gltf("linked/../tri.bin")), "");  // `..` from the link's target, sub/
  EXPECT_EQ(error_of(gltf("absolute.bin")), "");
}

// --- Refused: outside the folder ---------------------------------------------------------------

TEST_F(MeshReferencesTest, DotDotUriIsRefusedUnlessAllowed) {
  const fs::path file = gltf("../outside/secret.bin");
  EXPECT_EQ(error_of(file), outside_message(file, "../outside/secret.bin"));
  // Allowed, the file is read (and found too long for its byteLength: tinygltf's message).
  EXPECT_NE(error_of(file, true).find("File size mismatch"), std::string::npos);
  write("outside/tri.bin", triangle_buffer());
  EXPECT_EQ(error_of(gltf("../outside/tri.bin"), true), "");
  EXPECT_NE(error_of(gltf("../outside/tri.bin")), "");
  EXPECT_NE(error_of(gltf("sub/../../outside/tri.bin")), "");
  EXPECT_NE(error_of(gltf("..%2Foutside%2Ftri.bin")), "");
  EXPECT_NE(error_of(gltf("%2e%2e/outside/tri.bin")), "");
  EXPECT_NE(error_of(gltf("missing/../../outside/tri.bin")), "");
}

TEST_F(MeshReferencesTest, AbsoluteUriIsRefusedEvenInsideTheFolder) {
  const std::string inside = (meshes() / "tri.bin").string();
  const fs::path file = gltf(inside);
  EXPECT_EQ(error_of(file), outside_message(file, inside));
  EXPECT_EQ(error_of(file, true), "");
  EXPECT_EQ(error_of(gltf("%2F" + inside.substr(1))), outside_message(file, inside));
}

TEST_F(MeshReferencesTest, RefusalSaysNothingOfTheFileOutside) {
  // The same message, but for the uri, whether the file exists or not; no size, no error number.
  for (const auto& [present, absent] :
       {std::pair{std::string("../outside/secret.bin"), std::string("../outside/absent.bin")},
        std::pair{(outside() / "secret.bin").string(), (outside() / "absent.bin").string()}}) {
    const fs::path file = gltf(present);
    std::string a = error_of(file), b = error_of(gltf(absent));
    EXPECT_EQ(a, outside_message(file, present));
    EXPECT_EQ(b, outside_message(file, absent));
    a.replace(a.find(present), present.size(), "URI");
    b.replace(b.find(absent), absent.size(), "URI");
    EXPECT_EQ(a, b);
    EXPECT_EQ(a.find("12345"), std::string::npos) << a;
    EXPECT_EQ(a.find("bytes"), std::string::npos) << a;
    EXPECT_EQ(a.find("No such file"), std::string::npos) << a;
  }
}

TEST_F(MeshReferencesTest, SymbolicLinkLeadingOutsideIsRefused) {
  fs::create_symlink("../outside/secret.bin", meshes() / "relative.bin");
  fs::create_symlink(outside() / "secret.bin", meshes() / "absolute.bin");
  fs::create_symlink("../outside/absent.bin", meshes() / "dangling.bin");
  fs::create_directory_symlink("../outside", meshes() / "folder");
  fs::create_symlink("loop.bin", meshes() / "loop.bin");
  for (const std::string uri : {"relative.bin", "absolute.bin", "dangling.bin", "folder/secret.bin",
                                "sub/../folder/secret.bin"}) {
    const fs::path file = gltf(uri);
    EXPECT_EQ(error_of(file), outside_message(file, uri)) << uri;
  }
  // A link's target counts as the link: existing or not, the same answer.
  EXPECT_NE(error_of(gltf("loop.bin")).find("too many levels of symbolic links"),
            std::string::npos);
  write("outside/tri.bin", triangle_buffer());
  fs::create_symlink("../outside/tri.bin", meshes() / "good.bin");
  EXPECT_EQ(error_of(gltf("good.bin"), true), "");
  EXPECT_NE(error_of(gltf("good.bin")), "");
}

TEST_F(MeshReferencesTest, ImageUriLeadingOutsideIsRefusedToo) {
  const fs::path file = gltf("tri.bin", R"([{"uri": "../outside/secret.bin"}])");
  EXPECT_EQ(error_of(file), outside_message(file, "../outside/secret.bin"));
  // Images are not needed: a missing one inside the folder is no error, as before.
  EXPECT_EQ(error_of(gltf("tri.bin", R"([{"uri": "absent.png"}])")), "");
  EXPECT_EQ(error_of(gltf("tri.bin", R"([{"uri": "sub/tri.bin"}])")), "");
}

// --- Refused: not a regular file, too large ----------------------------------------------------

TEST_F(MeshReferencesTest, FolderOrNulByteUriIsRefused) {
  const fs::path file = gltf("sub");
  EXPECT_EQ(error_of(file), file.string() + ": uri \"sub\": it is a directory");
  EXPECT_EQ(error_of(gltf("tri.bin%00.png")),
            file.string() + ": uri \"tri.bin\\x00.png\": it contains a NUL byte");
}

TEST_F(MeshReferencesTest, BufferLargerThanTheLimitIsRefusedUnread) {
  // A sparse file: 2 GiB and one byte long, no disk used.
  const fs::path big = meshes() / "big.bin";
  write("meshes/big.bin", "");
  fs::resize_file(big, (std::uintmax_t{2} << 30) + 1);
  const fs::path file = gltf("big.bin");
  EXPECT_EQ(error_of(file), file.string() +
                                ": uri \"big.bin\": 2147483649 bytes, more than the limit of "
                                "2147483648 bytes");
}

TEST_F(MeshReferencesTest, FifoBufferFailsAtOnce) {
  ASSERT_EQ(::mkfifo((meshes() / "pipe.bin").c_str(), 0600), 0);
  ASSERT_EQ(::mkfifo((outside() / "pipe.bin").c_str(), 0600), 0);
  const fs::path file = gltf("pipe.bin");
  expect_refused(render(), file.string() +
                               ": uri \"pipe.bin\": it is not a regular file (a device, a FIFO "
                               "or a socket)");
  // Outside the folder, refused for that first; allowed, refused as a FIFO.
  gltf("../outside/pipe.bin");
  expect_refused(render(), outside_message(file, "../outside/pipe.bin"));
  expect_refused(render("--allow-outside"),
                 "uri \"../outside/pipe.bin\": it is not a regular file");
  // A device, and a FIFO as an image.
  gltf("/dev/zero");
  expect_refused(render("--allow-outside"), "uri \"/dev/zero\": it is not a regular file");
  gltf("tri.bin", R"([{"uri": "pipe.bin"}])");
  expect_refused(render(), "uri \"pipe.bin\": it is not a regular file");
}

TEST_F(MeshReferencesTest, ObjMaterialLibraryIsNeverOpened) {
  ASSERT_EQ(::mkfifo((meshes() / "pipe.mtl").c_str(), 0600), 0);
  write("meshes/tri.obj",
        "mtllib pipe.mtl ../outside/secret.bin /dev/zero\n"
        "usemtl x\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  write("scene.json", scene_with_mesh("meshes/tri.obj"));
  const test::CommandResult r = run_limited("check " + quoted(dir_ / "scene.json"));
  EXPECT_EQ(r.status, 0) << r.err;
}

// --- The command line --------------------------------------------------------------------------

TEST_F(MeshReferencesTest, CommandsRefuseOutsideReferencesUnlessAllowed) {
  write("outside/tri.bin", triangle_buffer());
  const fs::path file = gltf("../outside/tri.bin");
  const std::string message = outside_message(file, "../outside/tri.bin");
  // The scene's line and path, then the mesh file's message.
  expect_refused(render(), "scene.json:3: objects[0].shape.mesh.file: " + message);
  const test::CommandResult allowed = render("--allow-outside");
  EXPECT_EQ(allowed.status, 0) << allowed.err;
  EXPECT_TRUE(fs::exists(dir_ / "out.png"));

  const std::string scene = quoted(dir_ / "scene.json");
  for (const std::string& command :
       {"check " + scene, "info " + scene, "locate " + scene + " --direction 0,0,-1",
        "animate " + scene + " --frames 0-0 -o " + quoted(dir_ / "frame-%d.png") + " --quiet"}) {
    const test::CommandResult refused = run_limited(command);
    EXPECT_EQ(refused.status, 2) << command;
    EXPECT_NE(refused.err.find(message), std::string::npos) << command << ": " << refused.err;
    EXPECT_FALSE(fs::exists(dir_ / "frame-0.png")) << command;
    const test::CommandResult ok = run_limited(command + " --allow-outside");
    EXPECT_EQ(ok.status, 0) << command << ": " << ok.err;
  }
  // view needs a display; its option parses (the refusal comes before any window).
  const test::CommandResult view = run_limited("view " + scene);
  EXPECT_EQ(view.status, 2) << view.err;
  EXPECT_NE(view.err.find(message), std::string::npos) << view.err;
}

}  // namespace
}  // namespace lightcone
