// The text of a scene file into its JSON document, inside src/lightcone/io. Both throw
// InputError "FILE:LINE: (syntax): what is wrong".
#pragma once

#include <filesystem>
#include <string>

#include "lightcone/io/scene_document.hpp"

namespace lightcone {

// The file's text (within kMaxSceneFileBytes). A scene file is text: a NUL byte (which JSON
// never needs) would end the parser's input early while the line map read on.
std::string read_scene_text(const std::filesystem::path& file);

// The document (comments allowed), and whether a key repeats within one of its objects, which
// the document hides (it keeps the last one): only then need JsonLineMap scan for the repeats.
// Without `line_numbers` (a text that is no file) an error names `file` alone.
SceneJson parse_scene_document(const std::filesystem::path& file, const std::string& text,
                               bool& repeated_key, bool line_numbers = true);

}  // namespace lightcone
