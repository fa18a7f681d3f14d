// What the native viewer and the web page do alike on every frame: draw the scene as the
// flight's camera sees it, keeping its emission tables while they serve, and follow the
// automatic exposure.
#pragma once

#include <memory>

#include "lightcone/frame/emission.hpp"
#include "lightcone/raster/frame_target.hpp"
#include "lightcone/raster/raster_renderer.hpp"
#include "lightcone/scene/scene.hpp"

namespace lightcone {

struct FrameDraw {
  std::size_t triangles = 0;
  double doppler_min = 1, doppler_max = 1;  // over the bodies in view
};

// One picture of `scene` into `target`: resolved, tabulated, tessellated, drawn. `emission` is
// kept from frame to frame while it serves (EmissionTable::serves): it is built over a wider
// range of the Doppler factor than one frame needs, for a Scene that changes only in its camera
// and render settings.
FrameDraw draw_scene(RasterRenderer& renderer, const Scene& scene, const FloatTarget& target,
                     bool on_gpu, std::unique_ptr<EmissionTable>& emission);

// `lightcone view --benchmark`'s scripted flight, drawn `frames` times into `target` with the
// GL finished after each frame: from the scene's camera, up to 0.9c along the view within the
// first third, turning a little each frame. The native viewer and the web page run the same.
struct FlightBenchmark {
  double seconds = 0;
  std::size_t triangles = 0;  // per frame
};
FlightBenchmark benchmark_flight(RasterRenderer& renderer, const Scene& scene,
                                 const FloatTarget& target, int frames, bool on_gpu);

// The automatic exposure: metered on each frame (FloatTarget::metered_exposure, the rule of
// both renderers on a sample of the frame) and followed with a time constant of half a second,
// so that it does not pump; the first frame after a reset takes the metered value at once.
class ExposureFollower {
 public:
  double follow(const FloatTarget& frame, ToneMap tonemap, double seconds);
  void reset() { metered_yet_ = false; }
  double metered() const { return metered_; }

 private:
  double metered_ = 0;
  bool metered_yet_ = false;
};

}  // namespace lightcone
