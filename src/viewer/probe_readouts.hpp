// The viewer's instruments: a click on the picture probes that point (what `lightcone locate
// --pixel` answers: what is seen there, when its light left, the object's clock, D or g), a
// second click adds a ruler (the angle between the two look directions and the difference of
// their emission times), a third starts again; X clears them. Each probe is printed on stdout
// as locate --pixel's JSON line, so that a lesson can log it.
#pragma once

#include <functional>
#include <future>
#include <optional>
#include <string>
#include <vector>

#include "lightcone/frame/pixel_probe.hpp"
#include "lightcone/scene/scene.hpp"
#include "viewer/probe_text.hpp"

namespace lightcone {

// What the program probes with (pixel_probe.hpp's probe_pixel in `lightcone view`): the
// scene as drawn and an image point of it, which request_rules' probe_refused lets through.
// Called on a thread of its own.
using PixelProbeSource = std::function<PixelProbe(const Scene& scene, double x, double y)>;

class ProbeReadouts {
 public:
  static constexpr int kMaxProbes = 2;

  explicit ProbeReadouts(PixelProbeSource source) : source_(std::move(source)) {}
  ProbeReadouts(const ProbeReadouts&) = delete;
  ProbeReadouts& operator=(const ProbeReadouts&) = delete;

  bool available() const { return static_cast<bool>(source_); }
  // A click at image point (x, y) of `frame`, the scene as drawn: probed in the background, so
  // that no frame waits for it (a refusal is said at once, on stderr and in the readouts).
  void click(const Scene& frame, double x, double y);
  void clear();
  // Takes the probe in flight once it is done, and prints it; call once a frame, with the scene
  // as drawn (whose object names and units the readouts use).
  void poll(const Scene& frame);

  // Each probe's lines, numbered from 1, then the ruler's between the first two; seven
  // significant digits or more, as a worksheet quotes them.
  std::vector<std::string> lines() const;
  // The image points probed (the one in flight included), to mark on the picture.
  struct Mark {
    double x = 0, y = 0;
  };
  std::vector<Mark> marks() const;

 private:
  struct Done {
    PixelProbe probe;
    std::string json;
  };
  PixelProbeSource source_;
  std::vector<Done> done_;
  std::vector<std::string> lines_;  // done_'s readouts (probe_lines)
  std::optional<Mark> pending_mark_;
  std::future<Done> pending_;
  std::optional<std::string> refused_;
};

}  // namespace lightcone
