// Python values into the JSON text of the scene format, for Scene.from_dict and the values of
// overrides: checked as the program checks a scene file, early, as the value is walked.
#pragma once

#include <pybind11/pybind11.h>

#include <string>

namespace lightcone {

// A Python value as compact JSON text: the scene format as dicts, lists, strings, numbers,
// booleans and None, numpy's scalars as numbers and its arrays as lists. It is refused as the
// program refuses a scene file, and early, as it is walked: more than kMaxSceneFileBytes of text
// (the 64 MiB of a scene file) or nesting deeper than kMaxSceneNesting; and what JSON cannot
// hold (NaN, infinity, a key that is not a string, another type), each value named by its path:
// "<dict>: objects[2].velocity[0]: must be a finite number, got nan" (or for an override's
// value, "--set camera.velocity[0]: ...").
// `source` names the value in messages ("<dict>", or "--set" for the value of the override at
// `path`). Throws InputError.
std::string json_text(pybind11::handle value, const std::string& source, const std::string& path);

}  // namespace lightcone
