// A stage's block of the state written and read back through the state walk, as a snapshot
// carries it (engine/state_walk.h): a test restores a block into a state with this, then lets a
// fresh stage adopt it.
#pragma once

#include <stdexcept>

#include "engine/state_codec.h"
#include "engine/state_walk.h"

namespace serosa::test_blocks {

template <class Block>
Block copy(const Block& from) {
  StateWriter w;
  put(w, from);
  StateReader r(w.bytes(), "block");
  Block to;
  get(r, to);
  if (r.left() != 0) throw std::logic_error("block_copy: bytes left after the block");
  return to;
}

}  // namespace serosa::test_blocks
