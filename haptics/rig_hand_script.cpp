#include "haptics/rig_hand_script.h"

#include <algorithm>

namespace serosa::haptics {

std::vector<HandChange> hand_changes(const ToolPath& path, Hand hand) {
  std::vector<HandChange> out;
  for (std::size_t k = 0; k < path.samples.size(); ++k) {
    bool held_before = false;
    for (const ToolState& row : path.samples[k]) {
      const bool held = holder(row) == hand;
      if (held && !held_before) out.push_back({row.time_s, k});
      held_before = held;
    }
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const HandChange& a, const HandChange& b) { return a.t_s < b.t_s; });
  return out;
}

RigHand plan_rig_hand(const ToolPath& path, Hand hand, std::optional<std::size_t> first_tool,
                      const Trocar& trocar, std::vector<TrocarMap> to_handle) {
  RigHand r;
  r.first_tool = first_tool;
  r.trocar = trocar;
  r.to_handle = std::move(to_handle);
  r.to_handle.resize(path.tools.size());
  std::optional<std::size_t> now = first_tool;
  for (const HandChange& c : hand_changes(path, hand)) {
    if (now == c.tool) continue;  // it holds that one already: nothing to exchange
    r.exchanges.push_back(c);
    now = c.tool;
  }
  return r;
}

namespace {

// The last exchange at or before t_s, if any.
const HandChange* last_exchange(const RigHand& hand, double t_s) {
  const auto after = std::upper_bound(hand.exchanges.begin(), hand.exchanges.end(), t_s,
                                      [](double t, const HandChange& c) { return t < c.t_s; });
  return after == hand.exchanges.begin() ? nullptr : &*(after - 1);
}

}  // namespace

std::optional<std::size_t> held_tool(const RigHand& hand, double t_s) {
  const HandChange* e = last_exchange(hand, t_s);
  return e != nullptr ? std::optional<std::size_t>(e->tool) : hand.first_tool;
}

namespace {

// The joints of path tool k at t_s, carried to the handle's trocar.
JointState tool_joints(const ToolPath& path, const RigHand& hand, std::size_t k, double t_s) {
  return inverse(hand.trocar, hand.to_handle[k].pose(sample(path, k, t_s)));
}

// The instrument the handle held before exchange e.
std::optional<std::size_t> before(const RigHand& hand, const HandChange* e) {
  return e == hand.exchanges.data() ? hand.first_tool : std::optional<std::size_t>((e - 1)->tool);
}

}  // namespace

JointState hand_joints(const ToolPath& path, const RigHand& hand, double t_s) {
  const std::optional<std::size_t> k = held_tool(hand, t_s);
  if (!k) return JointState{};
  JointState q = tool_joints(path, hand, *k, t_s);
  const HandChange* e = last_exchange(hand, t_s);
  if (e == nullptr) return q;
  const std::optional<std::size_t> from = before(hand, e);
  const JointState was = from ? tool_joints(path, hand, *from, e->t_s) : q;
  const double out_s = std::max(was.insertion_m - kDrawnBackM, 0.0) / kHandWithdrawSpeedMS;
  const double since = t_s - e->t_s;
  if (since < out_s) {  // drawing back, turning towards the new instrument's path
    const double a = since / out_s;
    JointState d = q;
    d.pitch_rad = was.pitch_rad + a * (q.pitch_rad - was.pitch_rad);
    d.yaw_rad = was.yaw_rad + a * (q.yaw_rad - was.yaw_rad);
    d.roll_rad = was.roll_rad + a * (q.roll_rad - was.roll_rad);
    d.insertion_m = was.insertion_m - kHandWithdrawSpeedMS * since;
    return d;
  }
  const double in_s = std::max(since - out_s - kDrawnBackHoldS, 0.0);
  q.insertion_m = std::min(q.insertion_m, kDrawnBackM + kHandEntrySpeedMS * in_s);
  return q;
}

std::uint16_t hand_buttons(const ToolPath& path, const RigHand& hand, double t_s) {
  const std::optional<std::size_t> k = held_tool(hand, t_s);
  if (!k) return 0;
  std::uint32_t b = sample(path, *k, t_s).buttons & kDeviceButtons;
  if (const HandChange* e = last_exchange(hand, t_s); e != nullptr && t_s - e->t_s < kPressHoldS)
    b |= kExchangeButton;
  return static_cast<std::uint16_t>(b);
}

}  // namespace serosa::haptics
