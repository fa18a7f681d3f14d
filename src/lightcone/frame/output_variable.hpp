// The output variables beside the colour, by name (`lightcone render --aov`, `--map`, the Python
// module's aovs): what each is called, how it is labelled, its EXR channels, and whether it is
// defined near a black hole. The ray tracer computes them (trace/aov.hpp).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace lightcone {

enum class Aov {
  kDoppler,       // D = nu_camera / nu_emitter of the light seen
  kEmissionTime,  // the W-time at which that light left the surface (-inf: the sky)
  kDistance,      // its travel distance in the camera's frame (+inf: the sky)
  kObject,        // the index of the object in the scene's list (-1: the sky)
  kDepth,         // the distance along the camera's forward axis, camera frame (+inf: the sky)
  kNormal,        // the surface normal in the body's rest frame, 3 channels (0: the sky)
  kImageOrder,    // near a black hole: how often the ray swept pi about it (0 elsewhere)
};

// By name: doppler, emission_time, distance, object, depth, normal, image_order.
std::optional<Aov> aov_from_name(std::string_view name);
// The name of an output variable.
std::string aov_name(Aov aov);
// How `--map` labels it: the quantity and its unit (the scene's own units of time and length).
std::string aov_map_label(Aov aov);
// The EXR channel names of an output variable: its name, or name.X, name.Y, name.Z.
std::vector<std::string> aov_channel_names(Aov aov);

// Whether `aov` is defined near a black hole: doppler (the shift g, 0 for the shadow), object
// (-1 for the sky, the disk and the shadow) and image_order.
bool aov_near_black_hole(Aov aov);

}  // namespace lightcone
