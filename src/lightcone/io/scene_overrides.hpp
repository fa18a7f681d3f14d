// --set overrides ("key.path=value") applied to a parsed scene document before validation.
#pragma once

#include <string>

#include "lightcone/io/scene_document.hpp"

namespace lightcone {

// Replaces the value at the override's path with its value, parsed as JSON (or taken as a plain
// string when it is not valid JSON). Path components are separated by '.'; a numeric component
// indexes an array ("objects.0.velocity", also written "objects[0].velocity"), and the index
// one past the end appends. Missing objects on the way are created. Returns the readable path
// of the replaced value (as json_member_path/json_element_path build it), so that errors in it
// can be blamed on the override. Throws InputError "--set PATH: what is wrong".
std::string apply_scene_override(SceneJson& document, const std::string& override_text);

}  // namespace lightcone
