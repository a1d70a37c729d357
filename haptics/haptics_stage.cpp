#include "haptics/haptics_stage.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>

#include "engine/input_error.h"
#include "engine/instrument_hold.h"
#include "engine/jaw_range.h"
#include "engine/scene/tool_path.h"
#include "engine/sim_state.h"
#include "haptics/emulated_hands.h"
#include "haptics/emulated_rig.h"
#include "haptics/haptic_loop.h"
#include "haptics/script_device.h"
#include "haptics/usb_rig.h"

namespace serosa::haptics {

MouseHandle mouse_handle(const Tool& tool, std::size_t handle, const Vec3& aim_m,
                         const std::optional<ToolState>& rest_pose) {
  MouseHandle m;
  const Vec3 side = handle == 0 ? Vec3(-0.05, 0.0, 0.0) : Vec3(0.05, 0.0, 0.0);
  m.trocar.pivot_m = tool.trocar_m.value_or(Vec3(aim_m + Vec3(0.0, 0.12, 0.0) + side));
  const std::optional<Vec3> rest_tip =
      rest_pose
          ? std::optional<Vec3>(Vec3(rest_pose->tip_m[0], rest_pose->tip_m[1], rest_pose->tip_m[2]))
          : std::nullopt;
  Vec3 axis = rest_tip.value_or(aim_m) - m.trocar.pivot_m;
  if (axis.norm() < 1e-6) axis = Vec3(0.0, -1.0, 0.0);
  m.trocar.rotation = Quat::FromTwoVectors(Vec3::UnitZ(), axis.normalized());
  m.rest.insertion_m = (rest_tip ? 1.0 : 0.5) * axis.norm();
  if (rest_pose) {  // the roll that turns the jaw plane's normal (local +y) nearest the pose's
    const Quat q(rest_pose->quat_wxyz[0], rest_pose->quat_wxyz[1], rest_pose->quat_wxyz[2],
                 rest_pose->quat_wxyz[3]);
    const Vec3 shaft = m.trocar.rotation * Vec3::UnitZ();
    Vec3 want = q.normalized() * Vec3::UnitY();
    want -= want.dot(shaft) * shaft;
    if (want.norm() > 1e-6)  // Rz(roll) e_y = -sin(roll) e_x + cos(roll) e_y
      m.rest.roll_rad = std::atan2(-want.dot(m.trocar.rotation * Vec3::UnitX()),
                                   want.dot(m.trocar.rotation * Vec3::UnitY()));
  }
  return m;
}

Vec3 shaft_push_at_tip(const ToolReaction& r, const ToolState& tool) {
  const Quat q =
      Quat(tool.quat_wxyz[0], tool.quat_wxyz[1], tool.quat_wxyz[2], tool.quat_wxyz[3]).normalized();
  const Vec3 d = q * Vec3::UnitZ();
  const Vec3 axial = r.shaft_push_n.dot(d) * d;
  return axial + r.shaft_lever * (r.shaft_push_n - axial);
}

haptics::Trocar rig_trocar(const Tool& tool, std::size_t handle, const Vec3& aim_m) {
  return mouse_handle(tool, handle, aim_m).trocar;
}

namespace {

bool is_rig(DeviceKind k) { return k == DeviceKind::kRig || k == DeviceKind::kRigEmulated; }

// Stands in for the rig when the USB stack itself is unavailable (libusb cannot initialize: no
// usbfs, as in a container): never connected, so the loop renders zero force.
class NoRig final : public haptics::Device {
 public:
  bool poll(double, haptics::DeviceSample&) noexcept override { return false; }
  [[nodiscard]] bool connected() const noexcept override { return false; }
  void command(const haptics::DeviceCommand&) noexcept override {}
  [[nodiscard]] const char* name() const noexcept override { return "no-rig"; }
};

// Per hand, each instrument it held and the largest efforts the firmware was sent meanwhile.
nlohmann::json efforts_json(const haptics::EmulatedRigConfig& c,
                            const haptics::EmulatedRigStats& st) {
  nlohmann::json j = nlohmann::json::object();
  for (std::size_t h = 0; h < haptics::kHandles; ++h) {
    const auto& hand = c.hands[h];
    if (!hand || !hand->first_tool) continue;
    std::vector<std::size_t> held{*hand->first_tool};
    for (const haptics::HandChange& e : hand->exchanges) held.push_back(e.tool);
    nlohmann::json& out = j[h == 0 ? "left" : "right"];
    for (const std::size_t k : held)
      out[c.path.tools[k]] = {{"peak_torque_nm", st.peak_torque_nm[k][h]},
                              {"peak_insertion_n", st.peak_insertion_n[k][h]}};
  }
  return j;
}

// What the emulated rig's firmware saw: the state packets it sent, the force packets it decoded,
// and how long each state packet took to be answered (ms).
nlohmann::json emulated_rig_json(const haptics::EmulatedRig& rig) {
  const haptics::EmulatedRigStats st = rig.stats();
  std::vector<double> lat = rig.latencies();
  std::sort(lat.begin(), lat.end());
  const auto at = [&](double q) {
    return lat.empty()
               ? 0.0
               : 1e3 * lat[std::min(lat.size() - 1,
                                    static_cast<std::size_t>(q * static_cast<double>(lat.size())))];
  };
  nlohmann::json j = {{"packets_sent", st.packets_sent}, {"forces_ok", st.forces_ok},
                      {"forces_bad", st.forces_bad},     {"watchdog_trips", st.watchdog_trips},
                      {"latency_p50_ms", at(0.5)},       {"latency_p99_ms", at(0.99)}};
  j["efforts"] = efforts_json(rig.config(), st);
  return j;
}

}  // namespace

HapticsStage::HapticsStage(const Scene& scene, const HapticsStageOptions& options) {
  std::optional<DeviceKind> kind;
  std::optional<std::filesystem::path> script;
  for (std::size_t i = 0; i < scene.tools.size(); ++i) {
    const Tool& t = scene.tools[i];
    // A Python program poses its tools itself, between steps: no handle takes them.
    if (t.kind == ToolKind::kEndoscope || t.device.kind == DeviceKind::kPython) continue;
    const bool rig = is_rig(t.device.kind);
    // A rig tool with a hand starts in that handle; any other tool in the next free one.
    std::size_t h = 0;
    if (rig && t.hand)
      h = *t.hand == Hand::kLeft ? 0 : 1;
    else
      while (h < haptics::kHandles && m_tool[h]) ++h;
    if (h >= haptics::kHandles || m_tool[h]) {
      // Its handle is taken: a mouse or rig instrument waits in its port for an exchange (a
      // scripted one is not driven).
      if (!rig && t.device.kind != DeviceKind::kMouse) continue;
      if (kind && *kind != t.device.kind)
        throw InputError(scene.file.string(), 0,
                         "the haptic handles' instruments must share one device kind: tool '" +
                             t.name + "' is driven by " +
                             std::string(device_kind_name(t.device.kind)),
                         std::string(device_kind_name(*kind)));
      m_waiting.push_back(i);
      continue;
    }
    if (kind && *kind != t.device.kind)
      throw InputError(scene.file.string(), 0,
                       "the haptic handles' tools must share one device kind: tool '" + t.name +
                           "' is driven by " + std::string(device_kind_name(t.device.kind)),
                       std::string(device_kind_name(*kind)));
    kind = t.device.kind;
    if (!t.device.script.empty()) {  // a script, or the path an emulated rig plays
      if (script && *script != t.device.script)
        throw InputError(t.device.script.string(), 0,
                         "the haptic handles' tools must share one script file", script->string());
      script = t.device.script;
    }
    m_tool[h] = i;
    m_jaw_max[h] = max_jaw_rad(t.kind);
  }
  if (!kind)
    throw InputError(scene.file.string(), 0, "\"haptics\" needs an instrument to drive",
                     "a grasper or scissors with device = \"rig\", \"rig-emulated\", "
                     "\"mouse\" or \"script:FILE\"");
  m_kind = *kind;
  if (m_kind != DeviceKind::kScript) build_rack(scene, options);
  std::array<haptics::Trocar, haptics::kHandles> trocars{};
  if (m_kind == DeviceKind::kScript) {
    ToolPath path = read_tool_path(*script);
    std::array<std::optional<std::size_t>, haptics::kHandles> of_handle{};
    for (std::size_t h = 0; h < haptics::kHandles; ++h) {
      if (!m_tool[h]) continue;
      const Tool& t = scene.tools[*m_tool[h]];
      of_handle[h] = path.index_of(t.name);
      if (!of_handle[h])
        throw InputError(script->string(), 0, "no rows for tool '" + t.name + "'",
                         "rows whose tool column is '" + t.name + "'");
      const ToolState first = sample(path, *of_handle[h], 0.0);
      const Vec3 tip(first.tip_m[0], first.tip_m[1], first.tip_m[2]);
      trocars[h].pivot_m = t.trocar_m.value_or(tip);
      const Vec3 axis = tip - trocars[h].pivot_m;
      if (axis.norm() > 1e-9)
        trocars[h].rotation = Quat::FromTwoVectors(Vec3::UnitZ(), axis.normalized());
    }
    m_device = std::make_unique<haptics::ScriptDevice>(std::move(path), of_handle, trocars);
  } else if (is_rig(m_kind)) {
    haptics::UsbRigConfig rc;
    for (std::size_t h = 0; h < haptics::kHandles; ++h) {
      if (!m_tool[h]) continue;
      trocars[h] = rig_trocar(scene.tools[*m_tool[h]], h, options.aim_m);
      m_rest_pose[h] = haptics::forward(trocars[h], haptics::JointState{});  // at its port
    }
    rc.trocars = trocars;
    if (m_kind == DeviceKind::kRigEmulated && script) emulate_rig(scene, *script, trocars);
    try {
      auto rig = std::make_unique<haptics::UsbRig>(rc);
      m_rig = rig.get();
      m_device = std::move(rig);
      wait_for_rig(options.rig_wait_s);
    } catch (const std::runtime_error& e) {
      m_usb_error = e.what();
      m_device = std::make_unique<NoRig>();
    }
    if (!m_device->connected()) warn_not_connected(scene);
    m_reported_connected = m_device->connected();
  } else {
    haptics::MouseMapping map;
    for (std::size_t h = 0; h < haptics::kHandles; ++h) {
      if (!m_tool[h]) continue;
      const std::size_t tool = *m_tool[h];
      const MouseHandle mh =
          mouse_handle(scene.tools[tool], h, options.aim_m,
                       tool < options.rest_pose.size() ? options.rest_pose[tool] : std::nullopt);
      trocars[h] = mh.trocar;
      map.rest[h] = mh.rest;
      map.jaw_max_rad[h] = max_jaw_rad(scene.tools[tool].kind);
      m_rest_pose[h] = haptics::forward(mh.trocar, mh.rest);
    }
    auto mouse = std::make_unique<haptics::MouseKeyboardDevice>(trocars, map);
    m_mouse = mouse.get();
    m_device = std::move(mouse);
  }
  haptics::HapticLoopConfig c;
  c.trocars = trocars;
  c.realtime = options.realtime;
  c.gap_monitor = options.realtime;
  // The emulated link (umockdev, ioctl round trips) delivers packets less regularly than USB.
  if (m_kind == DeviceKind::kRigEmulated) c.device_timeout_s = 50e-3;
  // Only a rig's handles put force in a hand, where a tick's jitter is felt: the loop spins to
  // its deadlines for them alone. The mouse's and the script's loop sleeps to them (a tick
  // about 0.1 ms late at worst): the spin cost a fifth of a core, on two cores shared with the
  // solver and a software renderer.
  if (!is_rig(m_kind)) c.spin_s = 0.0;
  m_loop = std::make_unique<haptics::HapticLoop>(*m_device, m_model, c);
}

HapticsStage::~HapticsStage() { stop(); }

// Every instrument of the handles' device, in scene order: the handles' first two and those
// waiting in their ports. Each gets its port (a mouse handle's or a rig's, as its first handle
// would give it) and its rest.
void HapticsStage::build_rack(const Scene& scene, const HapticsStageOptions& options) {
  std::vector<std::size_t> tools(m_waiting);
  for (const auto& t : m_tool)
    if (t) tools.push_back(*t);
  std::sort(tools.begin(), tools.end());
  std::vector<haptics::RackInstrument> items;
  std::array<std::optional<std::size_t>, haptics::kHandles> held{};
  for (std::size_t k = 0; k < tools.size(); ++k) {
    const std::size_t i = tools[k];
    std::size_t h = i == m_tool[1] ? 1 : 0;
    if (m_tool[h] == i) held[h] = k;
    const Tool& tool = scene.tools[i];
    haptics::RackInstrument r;
    r.tool = i;
    r.jaw_max_rad = max_jaw_rad(tool.kind);
    if (is_rig(m_kind)) {
      r.trocar = rig_trocar(tool, h, options.aim_m);
    } else {
      const MouseHandle mh =
          mouse_handle(tool, h, options.aim_m,
                       i < options.rest_pose.size() ? options.rest_pose[i] : std::nullopt);
      r.trocar = mh.trocar;
      r.rest = mh.rest;
    }
    items.push_back(r);
    m_port.push_back(port_pose(r.trocar.pivot_m, r.trocar.rotation * Vec3::UnitZ()));
  }
  m_rack = std::make_unique<haptics::HandRack>(std::move(items), held);
}

// Handle h's button went down: it puts its instrument into its port and takes the next waiting.
void HapticsStage::exchange(std::size_t h, SimState& state) {
  const std::optional<std::size_t> from = m_rack->held(h);
  const std::optional<std::size_t> to = m_rack->exchange(h);
  if (!from || !to) return;  // no other instrument waits: the button does nothing
  const haptics::RackInstrument& next = m_rack->instruments()[*to];
  state.tools[m_rack->instruments()[*from].tool] = m_port[*from];
  m_tool[h] = next.tool;
  m_jaw_max[h] = next.jaw_max_rad;
  if (m_mouse != nullptr)
    m_mouse->reseat(h, next.rest, next.jaw_max_rad,
                    haptics::trocar_map(next.trocar, m_rack->handle_trocar(h)).rotation);
}

// Loop -> solver for a handle with a rack: its instrument's pose (in its port while it enters),
// held by the hand; the instruments no handle holds wait in their ports.
void HapticsStage::place_rack(SimState& state, std::size_t h, const ToolState& handle_pose) {
  const std::size_t k = *m_rack->held(h);
  ToolState t = m_rack->entering(h) ? m_port[k] : m_rack->to_instrument(h, handle_pose);
  if (!m_rack->entering(h)) t.buttons = handle_pose.buttons & kDeviceButtons;
  set_holder(t, h == 0 ? Hand::kLeft : Hand::kRight);
  state.tools[m_rack->instruments()[k].tool] = t;
}

void HapticsStage::emulate_rig(const Scene& scene, const std::filesystem::path& script,
                               const std::array<haptics::Trocar, haptics::kHandles>& trocars) {
  if (!haptics::umockdev_preload_active())
    throw std::runtime_error("device \"rig-emulated:" + script.string() +
                             "\" needs the process under umockdev-wrapper (serosa headless and "
                             "serosa run arrange that themselves)");
  haptics::EmulatedRigConfig c;
  c.path = read_tool_path(script);
  for (std::size_t h = 0; h < haptics::kHandles; ++h) {
    if (!m_tool[h]) continue;
    c.tool_of_handle[h] = c.path.index_of(scene.tools[*m_tool[h]].name);  // the loader checked
  }
  c.trocars = trocars;
  // The path's hand column plays each handle's exchanges as a trainee's hand would.
  c.hands = haptics::emulated_hands(scene, *m_rack, c.path);
  m_emulated = std::make_unique<haptics::EmulatedRig>(std::move(c));  // before the driver's libusb
}

void HapticsStage::wait_for_rig(double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (!m_rig->connected() && std::chrono::steady_clock::now() < end)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
}

void HapticsStage::warn_not_connected(const Scene& scene) const {
  std::string tools;
  for (const auto& t : m_tool) {
    if (!t) continue;
    if (!tools.empty()) tools.append(", ");
    tools.append("'").append(scene.tools[*t].name).append("'");
  }
  std::string hint;
  if (m_kind == DeviceKind::kRigEmulated && !haptics::umockdev_preload_active())
    hint = " (device \"rig-emulated\" needs the process under umockdev-wrapper)";
  if (!m_usb_error.empty()) hint.append(" (").append(m_usb_error).append(")");
  spdlog::warn(
      "haptics: rig not connected: tool(s) {} (device \"{}\", USB {:04x}:{:04x}) stay at rest "
      "with zero force until the rig is plugged in{}",
      tools, device_kind_name(m_kind), haptics::kRigVendorId, haptics::kRigProductId, hint);
}

bool HapticsStage::device_connected() const noexcept {
  return m_device != nullptr && m_device->connected();
}

bool HapticsStage::driven_by_rig() const noexcept { return is_rig(m_kind); }

bool HapticsStage::rig_was_connected() const noexcept {
  return m_rig != nullptr && m_rig->counters().connects > 0;
}

void HapticsStage::stop() {
  if (m_loop && m_loop->running()) m_loop->stop();
}

haptics::LoopStatus HapticsStage::status() const { return m_loop->status().load(); }

void HapticsStage::feed_pointer(const haptics::PointerInput& in) noexcept {
  if (m_mouse != nullptr) m_mouse->feed(in);
}

void HapticsStage::step(const StepContext& ctx, SimState& state) {
  // Solver -> loop: the model of the state as it enters this step.
  haptics::ContactModel model;
  model.step = ctx.step + 1;  // 0 means "no model yet"
  model.time_s = ctx.time_s;
  for (std::size_t h = 0; h < haptics::kHandles; ++h) {
    if (!m_tool[h] || *m_tool[h] >= state.tools.size()) continue;
    haptics::ToolContact& tc = model.tools[h];
    tc.sim_tip_m = state.tools[*m_tool[h]].tip_m;
    const auto& planes = state.events.contact_planes;
    if (*m_tool[h] < planes.size() && planes[*m_tool[h]]) {
      tc.contacts[0] = *planes[*m_tool[h]];
      tc.n_contacts = 1;
    }
    const auto& reactions = state.events.tool_reactions;
    if (*m_tool[h] < reactions.size()) {
      const ToolReaction& r = reactions[*m_tool[h]];
      tc.held_pull_N = {r.held_pull_n.x(), r.held_pull_n.y(), r.held_pull_n.z()};
      tc.jaw_torque_Nm = r.jaw_torque_nm;
      const Vec3 at_tip = shaft_push_at_tip(r, state.tools[*m_tool[h]]);
      tc.shaft_push_N = {at_tip.x(), at_tip.y(), at_tip.z()};
    }
    if (m_rack) tc = m_rack->to_handle(h, tc);
  }
  if (m_emulated) m_emulated->follow(ctx.time_s, ctx.dt_s);
  count_events(state);
  model.cut_events = m_cut_events;
  model.contact_events = m_contact_events;
  m_model.store(model);
  if (!m_started) {
    m_loop->start();
    m_started = true;
  }
  // Rig plugged or unplugged: say so once per change (the loop itself zeroes the force).
  if (m_rig != nullptr && m_rig->connected() != m_reported_connected) {
    m_reported_connected = !m_reported_connected;
    if (m_reported_connected)
      spdlog::info("haptics: rig connected");
    else
      spdlog::warn("haptics: rig not connected (unplugged): zero force until it is back");
  }
  // Loop -> solver: the newest state of each handle. Until the loop's first tick a scripted
  // handle keeps what the tools stage gave it; a mouse or rig handle rests where its device
  // starts it (not at the scene origin, inside the organs).
  if (m_rack)
    for (std::size_t k = 0; k < m_port.size(); ++k)
      state.tools[m_rack->instruments()[k].tool] = m_port[k];
  for (std::size_t h = 0; h < haptics::kHandles; ++h) {
    if (!m_tool[h] || *m_tool[h] >= state.tools.size()) continue;
    ToolState t = m_loop->tool_state(h).load();
    // A rig handle opens its instrument as far as the mouse and the scripts do, no further.
    if (is_rig(m_kind)) t.jaw_rad = std::clamp(t.jaw_rad, 0.0, m_jaw_max[h]);
    if (t.tick == 0) {
      if (!m_rest_pose[h]) continue;
      t = *m_rest_pose[h];
    }
    const bool pressed = (t.buttons & kExchangeButton) != 0;
    if (m_rack && pressed && !m_pressed[h] && t.tick > 0) exchange(h, state);
    m_pressed[h] = pressed;
    if (!m_rack) {
      state.tools[*m_tool[h]] = t;
      continue;
    }
    m_rack->follow(h, t);
    // The mouse's handle waits drawn back until this step has seen it so: a step slower than
    // the whole entry would otherwise never see it drawn back, and its instrument would wait.
    if (m_mouse != nullptr && !m_rack->entering(h)) m_mouse->admit(h);
    place_rack(state, h, t);
  }
}

// The loop marks a force event when these counters move: the cuts made so far (the cutting stage
// runs after this one, so events.cuts holds the previous step's), and every time a handle's tool
// starts or stops pressing on or holding tissue (its force on the tissue becomes or stops being
// non-zero).
void HapticsStage::count_events(const SimState& state) noexcept {
  m_cut_events += static_cast<std::uint32_t>(state.events.cuts.size());
  const auto& force = state.events.tool_force_n;
  for (std::size_t h = 0; h < haptics::kHandles; ++h) {
    const bool touching = m_tool[h] && *m_tool[h] < force.size() && force[*m_tool[h]].norm() > 0.0;
    if (touching != m_touching[h]) ++m_contact_events;
    m_touching[h] = touching;
  }
}

nlohmann::json HapticsStage::telemetry_json() {
  stop();
  std::ostringstream os;
  m_loop->telemetry().write_json(os);
  nlohmann::json j = nlohmann::json::parse(os.str());
  j["device"] = std::string(device_kind_name(m_kind));
  j["device_connected"] = device_connected();
  if (is_rig(m_kind)) {
    const haptics::UsbRigCounters n =
        m_rig != nullptr ? m_rig->counters() : haptics::UsbRigCounters{};
    // "not_connected_ticks": loop ticks that rendered zero because the rig was absent.
    j["rig"] = {
        {"connected", device_connected()},
        {"not_connected_ticks",
         m_loop->telemetry().zero_ticks[static_cast<std::size_t>(haptics::ZeroReason::kUnplugged)]},
        {"packets", n.packets},
        {"lost", n.lost},
        {"rejected", n.too_short + n.too_long + n.bad_checksum + n.bad_type_version},
        {"stalls", n.stalls},
        {"commands_sent", n.commands_sent},
        {"commands_dropped", n.commands_dropped},
        {"connects", n.connects},
        {"disconnects", n.disconnects}};
    if (!m_usb_error.empty()) j["rig"]["error"] = m_usb_error;
    if (m_emulated) j["rig"]["emulated"] = emulated_rig_json(*m_emulated);
  }
  return j;
}

}  // namespace serosa::haptics
