// SceneReader, inside src/lightcone/io: the sections of a scene document into the scene model.
// Its members are defined in scene_file.cpp, and those about light (materials, lights, the sky)
// in scene_light.cpp.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "lightcone/io/json_locator.hpp"
#include "lightcone/io/scene_file.hpp"
#include "lightcone/io/scene_value_reader.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone::scene_io {

// Validates the document and builds the scene. Every check names the path of the offending
// value; the line comes from the locator, or the message blames a --set override.
class SceneReader : public SceneValueReader {
 public:
  SceneReader(const std::filesystem::path& file, const JsonLineMap& lines,
              std::vector<std::string> overridden, SceneLoadReport& report,
              const SceneLoadOptions& options)
      : SceneValueReader(file, lines, std::move(overridden), options.line_numbers, options.folder),
        report_(report),
        options_(options) {}

  Scene read(const json& document);

 private:
  // A mesh or image file named at `path`, to be loaded once the whole document is valid (so that
  // a typo near the end does not wait for large files to load first).
  struct Asset {
    enum Kind { kMesh, kTexture, kSkyImage, kStars } kind;
    std::size_t object = 0;
    std::filesystem::path file;
    std::string path;
  };

  // --- Sections ---------------------------------------------------------------------------

  Camera camera(const Node& n) const;

  // The camera as an observer of every other speed: at its observation, and while its shutter
  // is open at the shutter's close and at every phase's end in between (a phase's gamma relative
  // to a body's phase is convex in each proper time, so the largest is at these ends), or every
  // keyframe in between. Not near a black hole: there the camera's velocity is measured by its
  // local static observer and a body's far away by its own, and the flat relative speed of the
  // two means nothing; each body's local speed is held to the limit instead
  // (check_line_near_hole).
  void add_camera_observers(const Camera& c);

  // "motion": {"phases": [{"duration": tau, "acceleration": [ax, ay, az]}, ...]} or
  // {"keyframes": [{"time": t, "position": [x, y, z]}, ...]}.
  BodyMotion motion(const Node& n) const;
  std::vector<Keyframe> keyframes(const Node& list) const;
  std::vector<AccelerationPhase> phases(const Node& n) const;

  // The motion of the body `n` whose world-line so far is `start`. Keyframes replace the
  // world-line; phases start from its event. Nowhere may the body come too close to the speed
  // of light, in W or relative to the camera: between any two keyframes, or at any phase's end
  // (the largest gamma of a phase is at one of its ends: max_relative_gamma).
  BodyMotion body_motion(const Node& n, const Node& m, WorldLine& start) const;

  // The array `n` of objects or lights (`noun`s), each read by `read`; no two may have the
  // same name.
  template <class T, class Read>
  void read_named(const Node& n, std::string_view noun, std::vector<T>& out, Read read);

  void read_objects(const Node& n, Scene& scene);
  void read_lights(const Node& n, Scene& scene);
  Object read_object(const Node& n, std::size_t index);
  Shape shape(const Node& n, std::size_t index);
  RenderSettings render(const Node& n) const;

  // --- Light (scene_light.cpp) ------------------------------------------------------------

  Material material(const Node& n, std::size_t index);
  Glossy glossy_layer(const Node& n) const;
  Light read_light(const Node& n) const;
  EmissionSpectrum emission_spectrum(const Node& n) const;
  Sky sky(const Node& n);
  void pattern(const Node& n, Sky& s);
  std::optional<SkyStars> sky_stars(const Node& n);

  // --- The black hole (scene_black_hole.cpp) ----------------------------------------------

  // "black_hole": one Schwarzschild hole at rest in W, `mass` the length GM/c^2; its disk's
  // radii, given in units of M, become lengths.
  BlackHole black_hole(const Node& n) const;
  AccretionDisk accretion_disk(const Node& n, double mass) const;

  // Near a hole (in any scene with one), the camera `n` (before the rest of it is read): at
  // r > 2M, where a static observer measures its velocity; no motion but a geodesic one, no
  // shutter open for a while and no proper time other than 0 without a geodesic motion (not
  // yet supported).
  void check_camera_near_hole(const Node& n) const;

  // Whether the `motion` node `m` is a geodesic about the hole: an object with "orbit"
  // or "fall".
  static bool geodesic_motion(const Node& m);

  // The geodesic motion `m` ({"orbit": {...}} or {"fall": {...}}) of the camera or object `n`
  // (`noun`, for messages), which needs a black hole. It says where and when the body is: an
  // orbit takes no position, time or velocity, a fall no time or velocity, and a fall's
  // position, where given, is where it is at proper time 0 (its start from rest, or where it
  // passes from infinity).
  HoleGeodesic geodesic(const Node& n, const Node& m, std::string_view noun) const;
  HoleOrbit orbit(const Node& o, std::string_view noun) const;
  HoleFall fall(const Node& n, const Node& f, std::string_view noun) const;
  // An object on a geodesic (its shape and scale read): its ball about its origin clears the
  // horizon on an orbit, and its world-line holds its point at coordinate time 0.
  void geodesic_object(const Node& m, Object& o) const;

  // Refuses, near a hole, the key `n` (`what`: motion, spin, ...) that is not yet supported
  // there: "WHAT is not yet supported near a black hole[MORE]".
  void refuse_near_hole(const Node& n, std::string_view what, std::string_view more = "") const;

  // The object or light `n` (`noun`) on the coordinate line `line`, near a hole: at rest at
  // r > 2M, or moving on a line that stays outside r = 2M and on which the speed the static
  // observers measure stays below c (and within the one speed limit).
  void check_line_near_hole(const Node& n, const WorldLine& line, std::string_view noun) const;

  // --- Files ------------------------------------------------------------------------------

  // The loaders' own InputError names the file; prefix where the scene names it. Other errors
  // from the decoding libraries are about the file too; running out of memory is not.
  template <class Load>
  auto load(const Asset& a, Load&& load_file) const;

  void load_assets(Scene& scene);

  // A spinning body's rim moves at rate times its radius about the origin (which needs the
  // meshes loaded): below the speed of light, and its fastest point, with the body's own motion
  // added (relativistic velocity addition), within the one limit in W and relative to the camera.
  void check_spins(const Scene& scene) const;

  // A texture or a clock's dial on a mesh is read at the mesh's texture coordinates: a mesh
  // without them would show one texel everywhere (which needs the meshes loaded).
  void check_texture_coordinates(const Scene& scene) const;

  // A lit material's texture is an albedo: every value in [0, 1] (PNG and JPEG always are; an
  // EXR need not be).
  void check_albedo(const Asset& a, const Image& image) const;

  std::optional<BlackHole> hole_;  // read before the camera, objects and lights
  WorldLine observation_;          // the camera's, read before the objects (for "seen_at")
  std::vector<std::pair<std::size_t, std::string>> spins_;  // spinning objects, path of rate
  // Objects whose material reads texture coordinates (a texture, a clock), path of the pattern.
  std::vector<std::pair<std::size_t, std::string>> uv_patterns_;
  SceneLoadReport& report_;
  const SceneLoadOptions options_;
  std::vector<Asset> assets_;
};

}  // namespace lightcone::scene_io
