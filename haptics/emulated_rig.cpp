#include "haptics/emulated_rig.h"

#include <linux/usbdevice_fs.h>
#include <sys/ioctl.h>
#include <umockdev.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>

#include "engine/seqlock.h"
#include "haptics/device.h"

namespace serosa::haptics {
namespace {

constexpr const char* kSysPath = "/sys/devices/pci0000:00/usb1/1-1";
constexpr const char* kDevNode = "/dev/bus/usb/001/002";

// sysfs + udev properties of a full-speed 1209:5E70 with one vendor interface, EP 0x81 IN and
// EP 0x01 OUT (interrupt, 64 bytes, bInterval 1): the descriptors of docs/rig-protocol.md.
constexpr const char* kDeviceText =
    "P: /devices/pci0000:00/usb1/1-1\n"
    "N: bus/usb/001/002\n"
    "E: SUBSYSTEM=usb\n"
    "E: DEVTYPE=usb_device\n"
    "E: DEVNAME=/dev/bus/usb/001/002\n"
    "E: BUSNUM=001\n"
    "E: DEVNUM=002\n"
    "E: PRODUCT=1209/5e70/100\n"
    "A: busnum=1\\n\n"
    "A: devnum=2\\n\n"
    "A: bConfigurationValue=1\\n\n"
    "A: speed=12\\n\n"
    "A: idVendor=1209\\n\n"
    "A: idProduct=5e70\\n\n"
    "H: descriptors="
    "12010002000000400912705e000101020001"
    "09022000010100803209040000"
    "02ff000000"
    "07058103400001"
    "07050103400001\n";

}  // namespace

struct EmulatedRig::Impl {
  EmulatedRigConfig c;
  UMockdevTestbed* tb = nullptr;
  UMockdevIoctlBase* handler = nullptr;
  mutable std::mutex mu;  // handler thread vs. the test/control thread (not the haptic loop)
  std::deque<UMockdevIoctlData*> pending_in;
  std::deque<UMockdevIoctlData*> completed_out;
  std::deque<UMockdevIoctlData*> discarded;
  std::deque<RigFault> faults;
  bool halted = false;
  bool unplugged = false;
  double t0 = 0.0;       // construction: the device clock
  double path_t0 = 0.0;  // path time 0, wall clock (until follow() is called)
  // follow(): written by the solver at every step, read by the handler thread. A seqlock, so
  // the solver's step never waits on the handler's mutex.
  struct PathClock {
    bool following = false;
    double anchor_s = 0.0;       // the simulated time given
    double anchor_wall_s = 0.0;  // when it was given
    double cap_s = 0.0;          // the path never runs past this
  };
  Seqlock<PathClock> clock{};
  double next_due = 0.0;
  std::uint32_t seq = 0;
  std::array<std::pair<std::uint32_t, double>, 256> delivered{};
  std::uint32_t last_answered = 0;
  std::vector<double> latencies;
  mutable EmulatedRigStats st;
  bool enable_flag = false;

  void drop_all() {
    for (auto* q : {&pending_in, &completed_out, &discarded}) {
      for (auto* d : *q) umockdev_ioctl_data_unref(d);
      q->clear();
    }
  }

  // Motors follow force packets only while the watchdog is fed.
  void update_watchdog(double now) const {
    const bool on = enable_flag && now - st.last_force_time_s <= c.watchdog_s;
    if (st.motors_on && !on) ++st.watchdog_trips;
    st.motors_on = on;
  }

  StatePacket make_state(double now) {
    StatePacket p;
    p.sequence = ++seq;
    p.device_time_us = static_cast<std::uint32_t>((now - t0) * 1e6);
    for (std::size_t h = 0; h < kHandles; ++h) {
      const double t = path_time(now);
      p.handles[h] = to_counts(c.calibration, joints_at(h, t));
      p.handles[h].buttons = buttons_at(h, t);
    }
    update_watchdog(now);
    p.status = static_cast<std::uint16_t>(
        (st.motors_on ? kStatusMotorsEnabled : 0) |
        (!st.motors_on && st.forces_ok > 0 ? kStatusWatchdogTripped : 0));
    return p;
  }

  double path_time(double now) const {
    const PathClock k = clock.load();
    if (!k.following) return now - path_t0;
    return std::min(k.anchor_s + (now - k.anchor_wall_s), k.cap_s);
  }

  // The clutch, pedal and handle buttons the path holds down (docs/rig-protocol.md).
  std::uint16_t buttons_at(std::size_t h, double t) const {
    return hand_buttons(c.path, *c.hands[h], t);
  }

  JointState joints_at(std::size_t h, double t) const {
    return hand_joints(c.path, *c.hands[h], t);
  }

  // The efforts commanded to each handle, counted against the instrument it holds now.
  void note_efforts(const ForcePacket& fp, double now) {
    if ((fp.flags & kForceEnable) == 0) return;
    const double t = path_time(now);
    for (std::size_t h = 0; h < kHandles; ++h) {
      const std::optional<std::size_t> k = held_tool(*c.hands[h], t);
      if (!k) continue;
      const HandleEffort& e = fp.handles[h];
      const double torque =
          std::max(std::abs(e.pitch_torque), std::abs(e.yaw_torque)) * kTorqueScaleNm;
      auto& tq = st.peak_torque_nm[*k][h];
      auto& in = st.peak_insertion_n[*k][h];
      tq = std::max(tq, torque);
      in = std::max(in, std::abs(e.insertion_force) * kForceScaleN);
    }
  }

  static void complete_reap(UMockdevIoctlClient* client, UMockdevIoctlData* arg,
                            UMockdevIoctlData* urb_data) {
    UMockdevIoctlData* ptr = umockdev_ioctl_data_resolve(arg, 0, sizeof(gpointer), nullptr);
    umockdev_ioctl_data_set_ptr(ptr, 0, urb_data);
    umockdev_ioctl_data_unref(ptr);
    umockdev_ioctl_data_unref(urb_data);  // the reply owns it now
    umockdev_ioctl_client_complete(client, 0, 0);
  }

  gboolean handle(UMockdevIoctlClient* client) {
    std::lock_guard<std::mutex> lock(mu);
    const gulong req = umockdev_ioctl_client_get_request(client);
    UMockdevIoctlData* arg = umockdev_ioctl_client_get_arg(client);
    const double now = monotonic_s();
    if (unplugged) {
      // Like the kernel after a disconnect (CAP_REAP_AFTER_DISCONNECT): the URBs still queued
      // can be reaped, killed with -ESHUTDOWN; then every ioctl fails with ENODEV.
      if (req == USBDEVFS_REAPURB || req == USBDEVFS_REAPURBNDELAY) {
        for (auto* q : {&discarded, &completed_out, &pending_in}) {
          if (q->empty()) continue;
          UMockdevIoctlData* u = q->front();
          q->pop_front();
          auto* urb = reinterpret_cast<usbdevfs_urb*>(u->data);
          if (q == &pending_in) {
            urb->actual_length = 0;
            urb->status = -ESHUTDOWN;
          }
          complete_reap(client, arg, u);
          return TRUE;
        }
      }
      umockdev_ioctl_client_complete(client, -1, ENODEV);
      return TRUE;
    }
    switch (req) {
      case USBDEVFS_GET_CAPABILITIES: {
        UMockdevIoctlData* d = umockdev_ioctl_data_resolve(arg, 0, sizeof(guint32), nullptr);
        const guint32 caps = USBDEVFS_CAP_ZERO_PACKET | USBDEVFS_CAP_NO_PACKET_SIZE_LIM |
                             USBDEVFS_CAP_REAP_AFTER_DISCONNECT;
        std::memcpy(d->data, &caps, sizeof(caps));
        umockdev_ioctl_data_unref(d);
        umockdev_ioctl_client_complete(client, 0, 0);
        return TRUE;
      }
      case USBDEVFS_CLAIMINTERFACE:
      case USBDEVFS_RELEASEINTERFACE:
      case USBDEVFS_RESET:
      case USBDEVFS_RESETEP:
      case USBDEVFS_SETINTERFACE:
        umockdev_ioctl_client_complete(client, 0, 0);
        return TRUE;
      case USBDEVFS_IOCTL:  // kernel driver detach/attach: there is none
        umockdev_ioctl_client_complete(client, -1, ENODATA);
        return TRUE;
      case USBDEVFS_CLEAR_HALT:
        halted = false;
        ++st.stalls_cleared;
        umockdev_ioctl_client_complete(client, 0, 0);
        return TRUE;
      case USBDEVFS_SUBMITURB: {
        UMockdevIoctlData* urb_data =
            umockdev_ioctl_data_resolve(arg, 0, sizeof(usbdevfs_urb), nullptr);
        auto* urb = reinterpret_cast<usbdevfs_urb*>(urb_data->data);
        UMockdevIoctlData* buf =
            umockdev_ioctl_data_resolve(urb_data, offsetof(usbdevfs_urb, buffer),
                                        static_cast<gsize>(urb->buffer_length), nullptr);
        umockdev_ioctl_data_unref(buf);
        if (urb->type != USBDEVFS_URB_TYPE_INTERRUPT ||
            (urb->endpoint != kRigStateEndpoint && urb->endpoint != kRigForceEndpoint)) {
          umockdev_ioctl_data_unref(urb_data);
          umockdev_ioctl_client_complete(client, -1, EINVAL);
          return TRUE;
        }
        if (urb->endpoint == kRigStateEndpoint) {
          if (next_due == 0.0) next_due = now;
          pending_in.push_back(urb_data);
        } else {
          ForcePacket fp;
          const auto* bytes = static_cast<const std::uint8_t*>(urb->buffer);
          if (decode_force(std::span<const std::uint8_t>(
                               bytes, static_cast<std::size_t>(urb->buffer_length)),
                           fp) == DecodeError::kOk) {
            ++st.forces_ok;
            st.last_force = fp;
            st.last_force_time_s = now;
            enable_flag = (fp.flags & kForceEnable) != 0;
            note_efforts(fp, now);
            const auto& d = delivered[fp.state_sequence % delivered.size()];
            if (d.first == fp.state_sequence && fp.state_sequence != last_answered) {
              latencies.push_back(now - d.second);
              last_answered = fp.state_sequence;
            }
          } else {
            ++st.forces_bad;
          }
          urb->actual_length = urb->buffer_length;
          urb->status = 0;
          completed_out.push_back(urb_data);
        }
        update_watchdog(now);
        umockdev_ioctl_client_complete(client, 0, 0);
        return TRUE;
      }
      case USBDEVFS_DISCARDURB: {
        const auto addr = reinterpret_cast<gulong>(*reinterpret_cast<void**>(arg->data));
        for (auto* q : {&pending_in, &completed_out}) {
          for (auto it = q->begin(); it != q->end(); ++it) {
            if ((*it)->client_addr == addr) {
              reinterpret_cast<usbdevfs_urb*>((*it)->data)->status = -ENOENT;
              discarded.push_back(*it);
              q->erase(it);
              umockdev_ioctl_client_complete(client, 0, 0);
              return TRUE;
            }
          }
        }
        umockdev_ioctl_client_complete(client, -1, EINVAL);
        return TRUE;
      }
      case USBDEVFS_REAPURB:
      case USBDEVFS_REAPURBNDELAY: {
        update_watchdog(now);
        if (!discarded.empty()) {
          UMockdevIoctlData* u = discarded.front();
          discarded.pop_front();
          complete_reap(client, arg, u);
          return TRUE;
        }
        if (!completed_out.empty()) {
          UMockdevIoctlData* u = completed_out.front();
          completed_out.pop_front();
          complete_reap(client, arg, u);
          return TRUE;
        }
        if (!pending_in.empty() && !faults.empty() && faults.front() == RigFault::kStall) {
          faults.pop_front();
          halted = true;
        }
        if (!pending_in.empty() && halted) {
          UMockdevIoctlData* u = pending_in.front();
          pending_in.pop_front();
          auto* urb = reinterpret_cast<usbdevfs_urb*>(u->data);
          urb->actual_length = 0;
          urb->status = -EPIPE;
          complete_reap(client, arg, u);
          return TRUE;
        }
        if (!pending_in.empty() && now >= next_due) {
          // One packet per period; after a pause the device sends its current state, no backlog.
          next_due = std::max(next_due + c.packet_period_s, now - c.packet_period_s);
          UMockdevIoctlData* u = pending_in.front();
          pending_in.pop_front();
          auto* urb = reinterpret_cast<usbdevfs_urb*>(u->data);
          std::array<std::uint8_t, kStatePacketSize> w{};
          const StatePacket p = make_state(now);
          encode_state(p, w);
          int len = static_cast<int>(kStatePacketSize);
          if (!faults.empty()) {
            const RigFault f = faults.front();
            faults.pop_front();
            if (f == RigFault::kShortPacket) len = 20;
            if (f == RigFault::kBadChecksum) w[30] ^= 0x04;
            if (f == RigFault::kBadVersion) {
              w[1] = 2;
              const std::uint16_t crc = crc16_ccitt(std::span<const std::uint8_t>(w.data(), 62));
              w[62] = static_cast<std::uint8_t>(crc & 0xff);
              w[63] = static_cast<std::uint8_t>(crc >> 8);
            }
          }
          len = std::min(len, urb->buffer_length);
          std::memcpy(urb->buffer, w.data(), static_cast<std::size_t>(len));
          urb->actual_length = len;
          urb->status = 0;
          delivered[p.sequence % delivered.size()] = {p.sequence, now};
          ++st.packets_sent;
          complete_reap(client, arg, u);
          return TRUE;
        }
        umockdev_ioctl_client_complete(client, -1, EAGAIN);
        return TRUE;
      }
      default:
        umockdev_ioctl_client_complete(client, -1, ENOTTY);
        return TRUE;
    }
  }

  static gboolean on_ioctl(UMockdevIoctlBase*, UMockdevIoctlClient* client, gpointer self) {
    return static_cast<Impl*>(self)->handle(client);
  }

  void add_device() {
    GError* err = nullptr;
    if (!umockdev_testbed_attach_ioctl(tb, kDevNode, handler, &err)) {
      std::string msg = "emulated rig: attaching the ioctl handler failed: ";
      msg.append(err ? err->message : "unknown error");
      if (err) g_error_free(err);
      throw std::runtime_error(msg);
    }
    if (!umockdev_testbed_add_from_string(tb, kDeviceText, &err)) {
      std::string msg = "emulated rig: adding the device failed: ";
      msg.append(err ? err->message : "unknown error");
      if (err) g_error_free(err);
      throw std::runtime_error(msg);
    }
  }
};

bool umockdev_preload_active() {
  const char* p = std::getenv("LD_PRELOAD");
  return p && std::strstr(p, "libumockdev-preload") != nullptr;
}

void ensure_umockdev_preload(char** argv) {
  if (umockdev_preload_active()) return;
  std::string asan = std::getenv("ASAN_OPTIONS") ? std::getenv("ASAN_OPTIONS") : "";
  if (!asan.empty()) asan.append(":");
  asan.append("verify_asan_link_order=0");
  setenv("ASAN_OPTIONS", asan.c_str(), 1);
  std::vector<char*> args;
  args.push_back(const_cast<char*>("umockdev-wrapper"));
  for (char** a = argv; *a; ++a) args.push_back(*a);
  args.push_back(nullptr);
  execvp("umockdev-wrapper", args.data());
  std::string msg = "cannot run under umockdev-wrapper (is the umockdev package installed?): ";
  msg.append(std::strerror(errno));
  throw std::runtime_error(msg);
}

EmulatedRig::EmulatedRig(EmulatedRigConfig c) : m(std::make_unique<Impl>()) {
  if (!umockdev_preload_active()) {
    throw std::runtime_error(
        "emulated rig: libumockdev-preload is not loaded (run under umockdev-wrapper)");
  }
  for (const auto& t : c.tool_of_handle) {
    if (t && *t >= c.path.tools.size()) {
      throw std::out_of_range("emulated rig: tool index " + std::to_string(*t) +
                              " is not a tool of " + c.path.file);
    }
  }
  for (std::size_t h = 0; h < kHandles; ++h)
    if (!c.hands[h]) c.hands[h] = RigHand{c.tool_of_handle[h], c.trocars[h], {}, {}};
  for (auto& hand : c.hands) hand->to_handle.resize(c.path.tools.size());
  m->st.peak_torque_nm.assign(c.path.tools.size(), {});
  m->st.peak_insertion_n.assign(c.path.tools.size(), {});
  m->c = std::move(c);
  m->t0 = monotonic_s();
  m->path_t0 = m->t0;
  m->latencies.reserve(1 << 16);
  m->tb = umockdev_testbed_new();
  m->handler = umockdev_ioctl_base_new();
  g_signal_connect_data(m->handler, "handle-ioctl", reinterpret_cast<GCallback>(&Impl::on_ioctl),
                        m.get(), nullptr, static_cast<GConnectFlags>(0));
  m->add_device();
}

EmulatedRig::~EmulatedRig() {
  {
    std::lock_guard<std::mutex> lock(m->mu);
    m->unplugged = true;
    m->drop_all();
  }
  g_object_unref(m->handler);
  g_object_unref(m->tb);
}

void EmulatedRig::follow(double sim_time_s, double step_s) {
  m->clock.store({true, sim_time_s, monotonic_s(), sim_time_s + step_s});
}

void EmulatedRig::unplug() {
  {
    std::lock_guard<std::mutex> lock(m->mu);
    if (m->unplugged) return;
    m->unplugged = true;  // from now on ioctls fail with ENODEV, like a vanished device
  }
  umockdev_testbed_uevent(m->tb, kSysPath, "remove");
  umockdev_testbed_remove_device(m->tb, kSysPath);
  umockdev_testbed_detach_ioctl(m->tb, kDevNode, nullptr);
}

void EmulatedRig::replug() {
  {
    std::lock_guard<std::mutex> lock(m->mu);
    if (!m->unplugged) return;
    m->drop_all();  // URBs of the old session nobody reaped
    m->unplugged = false;
    m->halted = false;
    m->next_due = 0.0;
    m->enable_flag = false;
  }
  m->add_device();
}

bool EmulatedRig::plugged() const {
  std::lock_guard<std::mutex> lock(m->mu);
  return !m->unplugged;
}

void EmulatedRig::inject(RigFault f) {
  std::lock_guard<std::mutex> lock(m->mu);
  m->faults.push_back(f);
}

EmulatedRigStats EmulatedRig::stats() const {
  std::lock_guard<std::mutex> lock(m->mu);
  m->update_watchdog(monotonic_s());
  return m->st;
}

std::vector<double> EmulatedRig::latencies() const {
  std::lock_guard<std::mutex> lock(m->mu);
  return m->latencies;
}

const EmulatedRigConfig& EmulatedRig::config() const { return m->c; }

JointState EmulatedRig::joints_at(std::size_t h, double t_s) const { return m->joints_at(h, t_s); }

}  // namespace serosa::haptics
