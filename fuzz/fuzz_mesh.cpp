// The mesh loaders: the first byte picks the format (OBJ, PLY, glTF, GLB), the rest is the file.
//
// The file is written to mesh/ in the harness's own folder, among the things a glTF's uris may
// name (the seeds in corpus/mesh/uri-* name them):
//   mesh/tri.bin, mesh/sub/buffer.bin   a one-triangle buffer (44 bytes), beside and below
//   mesh/dir/                           a folder
//   mesh/pipe                           a FIFO: refused by its status, never opened
//   mesh/link.bin -> ../outside/fifo    a symbolic link leading out of the folder
//   outside/secret.bin                  a triangle buffer outside the mesh file's folder
//   outside/fifo                        a FIFO outside (opening it would block)
// Outside files are not allowed (MeshLoadOptions::allow_outside is false), so the loader must
// open nothing outside mesh/, and no uri (../, absolute, percent-encoded, through a link)
// reaches past the harness's own folder. A watchdog thread holds that: it aborts (a crash, with
// the input, to libFuzzer) when inotify reports a file in outside/ opened or read, or when the
// FIFO there has a reader (the opening of which would otherwise just block).
#include <fcntl.h>
#include <poll.h>
#include <sys/inotify.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <thread>

#include "fuzz_support.hpp"
#include "lightcone/io/input_error.hpp"
#include "lightcone/io/mesh_file.hpp"

namespace {

std::string triangle_buffer() {
  std::string b(44, '\0');
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::uint16_t indices[3] = {0, 1, 2};
  std::memcpy(b.data(), positions, sizeof positions);
  std::memcpy(b.data() + 36, indices, sizeof indices);
  return b;
}

void lay_out_folder() {
  namespace fs = std::filesystem;
  const fs::path& dir = lightcone::fuzz::own_dir();
  const std::string buffer = triangle_buffer();
  const auto bytes = reinterpret_cast<const std::uint8_t*>(buffer.data());
  for (const char* name : {"mesh/tri.bin", "mesh/sub/buffer.bin", "outside/secret.bin"})
    lightcone::fuzz::input_file(name, bytes, buffer.size());
  std::error_code ec;
  fs::create_directories(dir / "mesh" / "dir", ec);
  ::mkfifo((dir / "mesh" / "pipe").c_str(), 0600);
  ::mkfifo((dir / "outside" / "fifo").c_str(), 0600);
  fs::create_symlink("../outside/fifo", dir / "mesh" / "link.bin", ec);
}

[[noreturn]] void escaped(const char* how) {
  std::fprintf(stderr, "fuzz_mesh: the loader %s outside the mesh file's folder\n", how);
  std::abort();
}

void watch_outside() {
  const std::filesystem::path outside = lightcone::fuzz::own_dir() / "outside";
  const int notify = ::inotify_init1(IN_CLOEXEC);
  if (notify < 0 || ::inotify_add_watch(notify, outside.c_str(), IN_OPEN | IN_ACCESS) < 0) {
    std::fprintf(stderr, "fuzz_mesh: cannot watch %s\n", outside.c_str());
    std::abort();
  }
  const std::string fifo = (outside / "fifo").string();
  std::thread([notify, fifo] {
    for (;;) {
      // Only a file in the folder counts: another process listing the temporary folder (a
      // `find /tmp`) opens the folder itself, an event without a name.
      pollfd p{notify, POLLIN, 0};
      if (::poll(&p, 1, 10) > 0) {
        alignas(inotify_event) char events[4096];
        const ssize_t n = ::read(notify, events, sizeof events);
        for (ssize_t at = 0; at < n;) {
          const auto* e = reinterpret_cast<const inotify_event*>(events + at);
          if (e->len > 0) escaped("opened a file");
          at += static_cast<ssize_t>(sizeof(inotify_event) + e->len);
        }
      }
      const int writer = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC);
      if (writer >= 0) escaped("opened a FIFO");  // only a reader lets this open succeed
    }
  }).detach();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool ready = (lay_out_folder(), watch_outside(), true);
  (void)ready;
  if (size < 1) return 0;
  static const char* const names[] = {"mesh/mesh.obj", "mesh/mesh.ply", "mesh/mesh.gltf",
                                      "mesh/mesh.glb"};
  const auto file = lightcone::fuzz::input_file(names[data[0] % 4], data + 1, size - 1);
  try {
    lightcone::MeshLoadReport report;
    lightcone::MeshLoadOptions options;
    options.allow_outside = false;
    lightcone::load_mesh_file(file, report, options);
  } catch (const lightcone::InputError&) {
  }
  return 0;
}
