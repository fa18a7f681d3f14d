// Where the lights' legs to lit points near a black hole start their solves: the last leg
// solved for each body, light and image order (physics/schwarzschild_lens.hpp's
// RayBetweenStart). Neighbouring points of a picture on one body have legs a little apart, whose
// roots a start from the last one finds in some five evaluations of the sweep fewer. A renderer
// keeps one per tile, begun afresh with each, so that the picture does not depend on which
// thread renders which tile (the legs are the same to the last bits, not always to every bit).
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include "lightcone/physics/schwarzschild_lens.hpp"

namespace lightcone {

class HoleLegStarts {
 public:
  static constexpr int kOrders = 2;  // the direct leg and the one round the far side
  HoleLegStarts(std::size_t bodies, std::size_t lights)
      : lights_(lights), starts_(bodies * lights * kOrders) {}
  RayBetweenStart& at(std::size_t body, std::size_t light, int order) {
    return starts_[(body * lights_ + light) * kOrders + static_cast<std::size_t>(order)];
  }
  // Forgets every start (a new tile).
  void clear() { std::fill(starts_.begin(), starts_.end(), RayBetweenStart{}); }

 private:
  std::size_t lights_;
  std::vector<RayBetweenStart> starts_;
};

}  // namespace lightcone
