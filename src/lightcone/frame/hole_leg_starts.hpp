// Where the lights' legs to lit points near a black hole start their solves: the last leg
// solved to a body for each light and image order (physics/schwarzschild_lens.hpp's
// RayBetweenStart). Neighbouring points of a picture on one body have legs a little apart,
// whose roots a start from the last one brackets in a few evaluations of the sweep. A renderer
// keeps one per tile, begun afresh with each, so that the picture does not depend on which
// thread renders which tile.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "lightcone/physics/schwarzschild_lens.hpp"

namespace lightcone {

class HoleLegStarts {
 public:
  static constexpr int kOrders = 2;  // the direct leg and the one round the far side
  explicit HoleLegStarts(std::size_t lights) : lights_(lights) {}
  // Forgets every start: a new tile.
  void next_tile() { ++tile_; }
  // The start for a leg of `light` and `order` to `body`, set by its solve: the last such leg's
  // in this tile, or none. Bodies share a light's few slots (a body evicts another of the same
  // slot), so that the memory does not grow with the scene; the slots are made at the first.
  RayBetweenStart& at(std::size_t body, std::size_t light, int order) {
    if (slots_.empty()) slots_.resize(lights_ * kOrders * kSlotsPerLeg);
    Slot& slot = slots_[(light * kOrders + static_cast<std::size_t>(order)) * kSlotsPerLeg +
                        body % kSlotsPerLeg];
    if (slot.tile != tile_ || slot.body != body) slot = {RayBetweenStart{}, body, tile_};
    return slot.start;
  }

 private:
  static constexpr std::size_t kSlotsPerLeg = 64;
  struct Slot {
    RayBetweenStart start;
    std::size_t body = 0;
    std::uint64_t tile = 0;
  };
  std::size_t lights_;
  std::uint64_t tile_ = 1;
  std::vector<Slot> slots_;
};

}  // namespace lightcone
