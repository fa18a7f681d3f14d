// The JSON scene format (docs/scene-format.md, schema/scene.schema.json) into the scene model.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "lightcone/io/mesh_file.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

// The deepest a scene document may nest its arrays and objects (a scene needs some 8 levels; each
// costs memory and stack to read): deeper is refused, "nested more than 64 levels deep".
inline constexpr int kMaxSceneNesting = 64;

struct SceneLoadOptions {
  MeshLoadOptions mesh;  // how the mesh files the scene names are read (allow_outside)
  // For a text that is no file (Python's Scene.from_dict, whose scene is named "<dict>"): false
  // gives messages without a line, "<dict>: objects[2].velocity: what is wrong", since the
  // text's lines are no one's to read.
  bool line_numbers = true;
  // Where relative paths (meshes, textures, the sky's image) are read from, instead of the scene
  // file's folder ("" for the current folder): for a text that is no file.
  std::optional<std::filesystem::path> folder;
};

struct SceneLoadReport {
  std::vector<std::string> warnings;  // e.g. degenerate triangles dropped from a mesh
};

// A scene file's render settings where it gives none: a picture that shows its moving bodies
// (automatic exposure on them, the hue-keeping filmic curve), where RenderSettings' own defaults
// keep the radiance as it is (exposure 0, clamped) for scenes built in code.
RenderSettings file_render_defaults();

// Parses and validates a scene file. `overrides` are "key.path=value" strings (from --set):
// the value is parsed as JSON (falling back to a plain string) and replaces the value at that
// path before validation. Comments are allowed; unknown keys are errors. Relative mesh, texture
// and sky image paths are resolved against the scene file's folder; a mesh file used by many
// objects is loaded once, as `options` say. Throws InputError "FILE:LINE: PATH: what is wrong"
// (for a value that came from --set: "--set PATH: what is wrong").
Scene load_scene_file(const std::filesystem::path& file, const std::vector<std::string>& overrides,
                      SceneLoadReport& report, const SceneLoadOptions& options = {});

// The same for a scene file's text: `file` names it in messages, and relative paths are
// resolved against its folder (it need not exist), or against options.folder where given.
Scene load_scene_text(std::string text, const std::filesystem::path& file,
                      const std::vector<std::string>& overrides, SceneLoadReport& report,
                      const SceneLoadOptions& options = {});

}  // namespace lightcone
