// What may be asked of a scene: the one place for the rules every door checks (the `lightcone`
// program, the Python module, the web page), so that each refuses the same requests with the
// same message. Each function returns why the request is refused, "SOURCE: FIELD: why" with
// SOURCE the scene's Scene::source, or nothing; a door shows that message as its error.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "lightcone/frame/locate.hpp"
#include "lightcone/frame/output_variable.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

// Whether any renderer can draw the scene: the camera's size and samples within the scene
// format's limits (a scene changed in code is checked again), and near a black hole what curved
// spacetime has: relativity and light delay on (it has no classical picture), each light met
// where its light left for the surface (docs/design/black-hole.md, "What is not drawn yet").
std::optional<std::string> scene_refused(const Scene& scene);

// The renderer a request names, as every front end takes it: "trace" (the ray tracer) or
// "raster" (the real-time renderer). Why another name is refused, or nothing.
std::optional<std::string> renderer_refused(std::string_view name);

// What a render is asked for beside the scene, by either renderer (both give every output
// variable).
struct RenderRequest {
  std::span<const Aov> aovs;  // output variables beside the colour
};

// A render: the scene; from a camera inside a black hole's horizon only the output variables
// that need no W time there (aov_needs_world_time).
std::optional<std::string> render_refused(const Scene& scene, const RenderRequest& request);

// A locate: the scene; near a black hole a camera outside the horizon (where W's time, and so
// an emission time, is defined) and a point at rest outside the horizon, from which light can
// leave.
std::optional<std::string> locate_refused(const Scene& scene, const LocateQuery& query);

// A probe as a door received it, before the scene is read: its pixel two numbers x, y, and no
// object named beside it (a probe finds what is seen). Why not, as "locate: ...", or nothing.
std::optional<std::string> probe_request_refused(std::span<const double> pixel, bool object_named);

// A probe of image point (x, y) (`locate --pixel`): the scene; a finite point of the picture,
// 0 <= x < width and 0 <= y < height; near a black hole a camera outside the horizon, as locate.
std::optional<std::string> probe_refused(const Scene& scene, double x, double y);

// A rendered picture the library may hand out: every value finite. A non-finite one is wrong,
// not merely dark or bright (an exposure or an emitter's luminance beyond float's range), and
// none is ever returned; `exposure` is the EV the render applied.
// `non_finite` is how many of its values are not finite, as expose() (tone_map.hpp) counts
// them while it scales the picture.
std::optional<std::string> picture_refused(const Scene& scene, std::size_t non_finite,
                                           double exposure);

}  // namespace lightcone
