// KeyClock: how long keys are held, from key events that arrive in batches (a window's event
// poll, once a frame). An event's own time is unknown, only the poll that delivered it, so a
// slow frame between a tap's press and its release would make the tap look like a hold. A press
// is dated by the poll that delivered it; a release by the poll before the one that delivered it
// (the last moment the key was surely still down). A release never reports longer than the key
// was down, and at most the two frames around it shorter: a tap a slow frame split stays a tap.
#pragma once

#include <cstddef>
#include <vector>

namespace serosa::render {

class KeyClock {
 public:
  explicit KeyClock(std::size_t keys) : m_down_at_s(keys, 0.0), m_down(keys, false) {}

  /// A poll begins at `now_s` (s, any steady clock): the events that follow came in before it.
  void poll(double now_s);
  /// `key` went down (a repeat of a key already down changes nothing).
  void press(std::size_t key);
  /// `key` went up: how long it had surely been down, s; < 0 when it was not down.
  double release(std::size_t key);
  /// How long `key` has been down at `now_s`, s; < 0 when it is up.
  [[nodiscard]] double held_s(std::size_t key, double now_s) const;

 private:
  double m_poll_s = 0.0;            // the current poll's start, s
  double m_previous_poll_s = 0.0;   // the one before, s
  std::vector<double> m_down_at_s;  // [keys] the poll that delivered each key's press, s
  std::vector<bool> m_down;         // [keys] whether each key is down
};

}  // namespace serosa::render
