// The output variables beside the colour, by name (`lightcone render --aov`, `--map`, the Python
// module's aovs): what each is called, how it is labelled, its EXR channels, and which need W's
// time at the camera. The ray tracer computes them (trace/aov.hpp); near a black hole each is
// taken along the curved ray (docs/design/black-hole.md, "Output variables").
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace lightcone {

enum class Aov {
  kDoppler,       // D = nu_camera / nu_emitter of the light seen (near a hole g; 0: its shadow)
  kEmissionTime,  // the W-time at which that light left the surface (-inf: the sky, the shadow)
  kDistance,      // its travel distance in the camera's frame (+inf: the sky, the shadow)
  kObject,        // the index of the object in the scene's list, or a code below
  kDepth,         // the distance times the look direction's cosine against the forward axis
  kNormal,        // the surface normal with W's axes, facing the ray, 3 channels (0: no surface)
  kImageOrder,    // near a black hole: how often the ray swept pi about it (0 elsewhere)
};

// The object variable where the ray met no object of the scene's list.
inline constexpr float kObjectSky = -1;     // the sky
inline constexpr float kObjectDisk = -2;    // a black hole's accretion disk
inline constexpr float kObjectShadow = -3;  // a black hole's shadow (the ray fell in)

// By name: doppler, emission_time, distance, object, depth, normal, image_order.
std::optional<Aov> aov_from_name(std::string_view name);
// The name of an output variable.
std::string aov_name(Aov aov);
// How `--map` labels it: the quantity and its unit (the scene's own units of time and length).
std::string aov_map_label(Aov aov);
// The EXR channel names of an output variable: its name, or name.X, name.Y, name.Z.
std::vector<std::string> aov_channel_names(Aov aov);

// Whether `aov` is measured from W's time at the camera (emission_time, and distance and depth,
// which near a black hole are the light's coordinate travel time): not defined for a camera
// inside a black hole's horizon, where W's time is not.
bool aov_needs_world_time(Aov aov);

}  // namespace lightcone
