// What the mesh formats' readers share, inside src/lightcone/io: errors naming the file (and
// line), the bounded read, the final checks every mesh passes, and text scanning.
#pragma once

#include <charconv>
#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "lightcone/io/mesh_file.hpp"
#include "lightcone/portable.hpp"

namespace lightcone::mesh_io {

// InputError "FILE: what" and "FILE:LINE: what".
[[noreturn]] void fail(const std::filesystem::path& file, std::string_view what);
[[noreturn]] void fail_at(const std::filesystem::path& file, std::size_t line,
                          std::string_view what);

// The mesh file's bytes, as scene files are read (regular files only, within
// kMaxAssetFileBytes).
std::string read_whole_file(const std::filesystem::path& file);

// Checks what every format guarantees the renderer (finite vertices, indices in range, texture
// coordinates per vertex, some triangle left) and drops degenerate triangles, counting them.
std::shared_ptr<Mesh> finish_mesh(std::shared_ptr<Mesh> mesh, const std::filesystem::path& file,
                                  MeshLoadReport& report);

// Whether every coordinate of `p` is finite.
bool finite(const Vec3& p);

std::string_view trim(std::string_view s);
std::vector<std::string_view> split_words(std::string_view s);

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
  const auto [end, ec] = lightcone::from_chars(s.data(), s.data() + s.size(), value);
  return ec == std::errc() && end == s.data() + s.size();
}

std::shared_ptr<Mesh> load_obj(const std::filesystem::path& file, MeshLoadReport& report);
std::shared_ptr<Mesh> load_ply(const std::filesystem::path& file, MeshLoadReport& report);
std::shared_ptr<Mesh> load_gltf(const std::filesystem::path& file, bool binary,
                                MeshLoadReport& report, const MeshLoadOptions& options);

}  // namespace lightcone::mesh_io
