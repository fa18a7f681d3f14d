// Where the lights' legs to lit points near a black hole start their solves: the last leg
// solved to a body for each light and image order (physics/schwarzschild_lens.hpp's
// RayBetweenStart). Neighbouring points of a picture on one body have legs a little apart,
// whose roots a start from the last one brackets in a few evaluations of the sweep. A renderer
// keeps one a thread and begins it afresh with each tile, so that the picture does not depend on
// which thread renders which tile.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "lightcone/physics/schwarzschild_lens.hpp"

namespace lightcone {

class HoleLegStarts {
 public:
  static constexpr int kOrders = 2;  // the direct leg and the one round the far side
  // Forgets every start: tile `tile` (> 0, each tile of a render its own) begins.
  void begin_tile(std::uint64_t tile) { tile_ = tile; }
  // The start for a leg of `light` and `order` to `body`, set by its solve: the last such leg's
  // in this tile, or none. Bodies share a light's few slots (a body evicts another of the same
  // slot), so that the memory does not grow with the scene; a light's slots are made at its
  // first leg.
  RayBetweenStart& at(std::size_t body, std::size_t light, int order) {
    const std::size_t first = (light * kOrders + static_cast<std::size_t>(order)) * kSlotsPerLeg;
    if (slots_.size() < first + kSlotsPerLeg) slots_.resize(first + kSlotsPerLeg);
    Slot& slot = slots_[first + body % kSlotsPerLeg];
    if (slot.tile != tile_ || slot.body != body) slot = {RayBetweenStart{}, body, tile_};
    return slot.start;
  }

 private:
  static constexpr std::size_t kSlotsPerLeg = 64;
  struct Slot {
    RayBetweenStart start;
    std::size_t body = 0;
    std::uint64_t tile = 0;  // none
  };
  std::uint64_t tile_ = 0;
  std::vector<Slot> slots_;
};

}  // namespace lightcone
