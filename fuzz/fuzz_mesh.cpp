// The mesh loaders: the first byte picks the format (OBJ, PLY, glTF, GLB), the rest is the file.
#include "fuzz_support.hpp"
#include "lightcone/io/input_error.hpp"
#include "lightcone/io/mesh_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  static const char* const names[] = {"mesh.obj", "mesh.ply", "mesh.gltf", "mesh.glb"};
  const auto file = lightcone::fuzz::input_file(names[data[0] % 4], data + 1, size - 1);
  try {
    lightcone::MeshLoadReport report;
    lightcone::load_mesh_file(file, report);
  } catch (const lightcone::InputError&) {
  }
  return 0;
}
