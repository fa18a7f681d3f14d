// The JSON scene format (docs/scene-format.md, schema/scene.schema.json) into the scene model.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "lightcone/io/mesh_file.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

struct SceneLoadOptions {
  MeshLoadOptions mesh;  // how the mesh files the scene names are read (allow_outside)
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
// resolved against its folder (it need not exist).
Scene load_scene_text(std::string text, const std::filesystem::path& file,
                      const std::vector<std::string>& overrides, SceneLoadReport& report,
                      const SceneLoadOptions& options = {});

}  // namespace lightcone
