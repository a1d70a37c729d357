// BoundBlock<T>: where a stage (or a part of one) finds its block of the whole state
// (engine/state_blocks.h). The stage binds it to the block in the SimState it steps at the start
// of every step and when a restored state is adopted (Stage::adopt), and reads and writes the
// block through it; the block's data lives in SimState only. Before its first bind it reads a
// zero block of its own (a report asked for before the first step), which the first step's bind
// leaves behind. A caller keeps the SimState alive while it asks the stage about it.
#pragma once

#include <utility>

namespace serosa {

template <class T>
class BoundBlock {
 public:
  BoundBlock() = default;
  /// A zero block shaped by the stage before the first step (sizes per tool, per target).
  explicit BoundBlock(T unbound) : m_unbound(std::move(unbound)) {}
  // A copy (or a move) reads the same state's block when the original was bound, else its own
  // copy of the zero block.
  BoundBlock(const BoundBlock& o)
      : m_unbound(o.m_unbound), m_block(o.bound() ? o.m_block : &m_unbound) {}
  BoundBlock& operator=(const BoundBlock& o) {
    if (this == &o) return *this;
    m_unbound = o.m_unbound;
    m_block = o.bound() ? o.m_block : &m_unbound;
    return *this;
  }
  ~BoundBlock() = default;

  /// From now on the block is `block` (a field of the SimState being stepped).
  void bind(T& block) noexcept { m_block = &block; }
  [[nodiscard]] bool bound() const noexcept { return m_block != &m_unbound; }
  /// The block of the state last bound, or the zero one before any.
  [[nodiscard]] T& operator*() noexcept { return *m_block; }
  [[nodiscard]] const T& operator*() const noexcept { return *m_block; }
  [[nodiscard]] T* operator->() noexcept { return m_block; }
  [[nodiscard]] const T* operator->() const noexcept { return m_block; }
  /// The zero block shaped before the first step, to start a state's block from.
  [[nodiscard]] const T& unbound() const noexcept { return m_unbound; }

 private:
  T m_unbound;
  T* m_block = &m_unbound;
};

}  // namespace serosa
