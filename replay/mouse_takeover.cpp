#include "replay/mouse_takeover.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "engine/hook.h"
#include "engine/instrument_hold.h"
#include "engine/jaw_range.h"
#include "engine/scope_view.h"
#include "replay/replay_controller.h"

namespace serosa::replay {

using namespace serosa::app;  // the driver, the composition and the window's parts
namespace {

static_assert(haptics::kHandles == 2, "a hand's other hand is 1 - h");

bool instrument(const Tool& t) { return t.kind != ToolKind::kEndoscope; }

Hand hand_of(std::size_t h) { return h == 0 ? Hand::kLeft : Hand::kRight; }

// A fresh state with zero padding: the state hash covers the whole struct, and a replay reads the
// recording into zeroed ToolStates.
ToolState zeroed() {
  ToolState s;
  std::memset(static_cast<void*>(&s), 0, sizeof s);
  return s;
}

// The instruments the hands take at the branch: those the recording's hands held (a hand that held
// none stays idle until X); a recording without hands (a script's) gives them the first two
// instruments (scene order).
std::array<std::optional<std::size_t>, haptics::kHandles> first_held(
    const std::vector<Tool>& scene, const std::vector<ToolState>& tools, bool hands) {
  std::array<std::optional<std::size_t>, haptics::kHandles> held{};
  const std::size_t n = std::min(scene.size(), tools.size());
  std::size_t next = 0;
  for (std::size_t h = 0; h < haptics::kHandles; ++h)
    for (std::size_t i = hands ? 0 : next; i < n && !held[h]; ++i) {
      const bool take = instrument(scene[i]) && (!hands || holder(tools[i]) == hand_of(h));
      if (take) held[h] = i;
      next = i + 1;
    }
  return held;
}

}  // namespace

MouseTakeover::MouseTakeover(const Scene& scene, const std::vector<ToolState>& tools,
                             const haptics::MouseMapping& mapping)
    : m_tools(scene.tools), m_base_map(mapping), m_left(scene.tools.size(), false) {
  m_hands = std::any_of(tools.begin(), tools.end(),
                        [](const ToolState& t) { return holder(t) || in_port(t); });
  const auto held = first_held(m_tools, tools, m_hands);
  for (std::size_t h = 0; h < haptics::kHandles; ++h)
    if (held[h]) seat(h, *held[h], tools[*held[h]], m_initial);
  // The initial input holds what the hands took: the jaws as recorded, the buttons as recorded.
  for (std::size_t h = 0; h < haptics::kHandles; ++h) {
    m_initial.jaw_fraction[h] = m_seat[h].recorded_jaw_fraction;
    m_initial.buttons[h] = m_tool[h] ? tools[*m_tool[h]].buttons : 0u;
    m_seat[h].base = m_initial;
  }
  for (std::size_t i = 0; i < m_tools.size() && i < tools.size() && !m_scope; ++i) {
    if (instrument(m_tools[i]) || !scope_posed(tools[i])) continue;
    m_scope_tool = i;
    m_scope = std::make_unique<window::ScopeControl>(m_tools[i], tools[i]);
    if ((tools[i].buttons & kScopeAngledButton) != 0) m_scope->toggle_optic();  // as recorded
  }
}

MouseTakeover::~MouseTakeover() = default;

// Hand h's trocar on the shaft line through `pose` (an instrument in its port: through its port),
// its device at rest there.
void MouseTakeover::seat(std::size_t h, std::size_t tool, const ToolState& pose,
                         const haptics::PointerInput& in) {
  const Tool& t = m_tools[tool];
  const Quat q =
      Quat(pose.quat_wxyz[0], pose.quat_wxyz[1], pose.quat_wxyz[2], pose.quat_wxyz[3]).normalized();
  const Vec3 tip(pose.tip_m[0], pose.tip_m[1], pose.tip_m[2]);
  const Vec3 shaft = q * Vec3::UnitZ();
  const bool ported = in_port(pose);
  double length = t.trocar_m ? std::max((tip - *t.trocar_m).norm(), 1e-3) : 0.1;
  haptics::Trocar trocar;
  trocar.pivot_m = !ported      ? Vec3(tip - length * shaft)
                   : t.trocar_m ? *t.trocar_m
                                : Vec3(tip + kPortOutsideM * shaft);
  trocar.rotation = q;
  if (ported) length = m_base_map.min_insertion_m;  // it enters, just inside its trocar
  haptics::MouseMapping map = m_base_map;
  map.rest[h] = haptics::JointState{};
  map.rest[h].insertion_m = length;
  map.rest[h].jaw_rad = pose.jaw_rad;
  map.max_insertion_m = std::max(map.max_insertion_m, 2.0 * length);
  map.min_insertion_m = std::min(map.min_insertion_m, length);
  map.jaw_max_rad[h] = std::max(max_jaw_rad(t.kind), pose.jaw_rad);
  m_tool[h] = tool;
  m_trocars[h] = trocar;
  m_device[h] = std::make_unique<haptics::MouseKeyboardDevice>(
      std::array<haptics::Trocar, haptics::kHandles>{trocar, trocar}, map);
  Seat& s = m_seat[h];
  s.base = in;
  s.recorded_jaw_fraction = map.jaw_max_rad[h] > 0.0 ? pose.jaw_rad / map.jaw_max_rad[h] : 0.0;
  s.recorded_buttons = pose.buttons & ~kInPortBit;
  if (m_hands) {  // a recording with hands: this hand holds it now
    ToolState b = pose;
    b.buttons = s.recorded_buttons;
    set_holder(b, hand_of(h));
    s.recorded_buttons = b.buttons;
  }
  s.jaw_held = true;
  m_left[tool] = false;
}

// Hand h lets go of its instrument: it stays where the last step left it, pedal up, held by none.
void MouseTakeover::let_go(std::size_t h, const std::vector<ToolState>& tools) {
  if (!m_tool[h]) return;
  const std::size_t i = *m_tool[h];
  m_tool[h].reset();
  m_device[h].reset();
  if (i >= tools.size()) return;
  ToolState s = tools[i];
  s.buttons &= ~kPedalButton;
  if (holder(s)) set_holder(s, std::nullopt);
  m_left[i] = true;
  m_let_go.push_back({i, s});
}

void MouseTakeover::take(std::size_t h, std::size_t tool, const std::vector<ToolState>& tools,
                         const haptics::PointerInput& in) {
  if (h >= haptics::kHandles) throw std::out_of_range("hand " + std::to_string(h));
  if (tool >= m_tools.size() || tool >= tools.size())
    throw std::out_of_range("tool " + std::to_string(tool));
  if (!instrument(m_tools[tool]))
    throw std::invalid_argument("'" + m_tools[tool].name +
                                "' is the endoscope: the scope control drives it");
  if (m_tool[1 - h] == tool)
    throw std::invalid_argument("the other hand holds '" + m_tools[tool].name + "'");
  if (m_tool[h] == tool) return;
  let_go(h, tools);
  std::erase_if(m_let_go, [&](const TakeoverInput& t) { return t.tool == tool; });
  seat(h, tool, tools[tool], in);
}

std::optional<std::size_t> MouseTakeover::next_instrument(std::size_t h) const {
  const std::size_t n = m_tools.size();
  const std::size_t start = m_tool[h] ? *m_tool[h] + 1 : 0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = (start + k) % n;
    if (instrument(m_tools[i]) && m_tool[h] != i && m_tool[1 - h] != i) return i;
  }
  return std::nullopt;
}

// Each press of X since the last poll gives the hand the next instrument (as in the session).
void MouseTakeover::exchange_if_asked(const haptics::PointerInput& in,
                                      const std::vector<ToolState>& tools) {
  for (std::size_t h = 0; h < haptics::kHandles; ++h) {
    for (; m_exchanges_seen[h] != in.exchanges[h]; ++m_exchanges_seen[h])
      if (const std::optional<std::size_t> next = next_instrument(h)) take(h, *next, tools, in);
  }
}

// What hand h's device sees: the input since its instrument was taken, on its own handle; the
// jaws the recorded opening until the input asks for another. X is the takeover's, not the
// device's (its handle button would reach the tool's buttons).
haptics::PointerInput MouseTakeover::device_input(std::size_t h, const haptics::PointerInput& in) {
  Seat& s = m_seat[h];
  haptics::PointerInput d{};
  for (std::size_t k = 0; k < 3; ++k) d.move_m[h][k] = in.move_m[h][k] - s.base.move_m[h][k];
  d.depth_steps[h] = in.depth_steps[h] - s.base.depth_steps[h];
  d.roll_steps[h] = in.roll_steps[h] - s.base.roll_steps[h];
  d.homes[h] = in.homes[h] - s.base.homes[h];
  if (in.jaw_fraction[h] != s.base.jaw_fraction[h]) s.jaw_held = false;
  d.jaw_fraction[h] = s.jaw_held ? s.recorded_jaw_fraction : in.jaw_fraction[h];
  return d;
}

std::vector<TakeoverInput> MouseTakeover::poll(const haptics::PointerInput& in, double t_s,
                                               std::uint64_t step,
                                               const std::vector<ToolState>& tools) {
  exchange_if_asked(in, tools);
  std::vector<TakeoverInput> out;
  out.swap(m_let_go);
  for (std::size_t h = 0; h < haptics::kHandles; ++h) {
    if (!m_tool[h]) continue;
    m_device[h]->feed(device_input(h, in));
    haptics::DeviceSample sample;
    if (!m_device[h]->poll(t_s, sample)) continue;
    ToolState s = zeroed();
    s.tip_m = sample.pose[h].tip_m;
    s.quat_wxyz = sample.pose[h].quat_wxyz;
    s.jaw_rad = sample.pose[h].jaw_rad;
    s.tick = step;
    s.time_s = t_s;
    // The recorded buttons, with the device's bits the input toggled since (P: the pedal).
    s.buttons =
        m_seat[h].recorded_buttons ^ ((in.buttons[h] ^ m_seat[h].base.buttons[h]) & kDeviceButtons);
    out.push_back({*m_tool[h], s});
  }
  if (m_scope) {
    ToolState s = m_scope->pose().load();
    s.tick = step;
    s.time_s = t_s;
    out.push_back({*m_scope_tool, s});
  }
  return out;
}

void MouseTakeover::apply(const haptics::PointerInput& in, ReplayController& replay) {
  for (const TakeoverInput& t :
       poll(in, replay.time_s(), replay.steps_taken(), replay.state().tools))
    replay.set_tool_input(t.tool, t.input);
}

std::vector<std::size_t> MouseTakeover::left_tools() const {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < m_left.size(); ++i)
    if (m_left[i]) out.push_back(i);
  return out;
}

}  // namespace serosa::replay
