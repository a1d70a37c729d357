#include "haptics/usb_rig.h"

#include <libusb-1.0/libusb.h>
#include <spdlog/spdlog.h>
#include <time.h>

#include <cerrno>
#include <stdexcept>
#include <string>

namespace serosa::haptics {
namespace {

int hotplug_cb(libusb_context*, libusb_device*, libusb_hotplug_event event, void* user) {
  auto* flags = static_cast<std::array<std::atomic<bool>*, 2>*>(user);
  if (event == LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED) (*flags)[0]->store(true);
  if (event == LIBUSB_HOTPLUG_EVENT_DEVICE_LEFT) (*flags)[1]->store(true);
  return 0;  // stay registered
}

}  // namespace

UsbRig::UsbRig(const UsbRigConfig& c) : m_c(c) {
  const int rc = libusb_init(&m_ctx);
  if (rc != 0) {
    std::string msg = "usb rig: libusb_init failed: ";
    msg.append(libusb_error_name(rc));
    throw std::runtime_error(msg);
  }
  sem_init(&m_wake, 0, 0);
  for (auto& t : m_in) t = libusb_alloc_transfer(0);
  m_out = libusb_alloc_transfer(0);
  if (libusb_has_capability(LIBUSB_CAP_HAS_HOTPLUG)) {
    static_assert(sizeof(int) == sizeof(libusb_hotplug_callback_handle));
    m_hotplug_flags = {&m_arrived, &m_left};
    libusb_hotplug_callback_handle h = 0;
    const int hr = libusb_hotplug_register_callback(
        m_ctx,
        static_cast<libusb_hotplug_event>(LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED |
                                          LIBUSB_HOTPLUG_EVENT_DEVICE_LEFT),
        LIBUSB_HOTPLUG_NO_FLAGS, m_c.vendor_id, m_c.product_id, LIBUSB_HOTPLUG_MATCH_ANY,
        hotplug_cb, &m_hotplug_flags, &h);
    if (hr == 0) {
      m_hotplug_handle = h;
      m_hotplug = true;
    } else {
      spdlog::warn("usb rig: hotplug registration failed ({}); polling for the rig instead",
                   libusb_error_name(hr));
    }
  }
  m_events = std::thread([this] { event_thread(); });
  m_writer = std::thread([this] { writer_thread(); });
}

UsbRig::~UsbRig() {
  m_stop.store(true);
  sem_post(&m_wake);
  if (m_writer.joinable()) m_writer.join();
  if (m_events.joinable()) m_events.join();
  if (m_hotplug) libusb_hotplug_deregister_callback(m_ctx, m_hotplug_handle);
  for (auto* t : m_in) libusb_free_transfer(t);
  libusb_free_transfer(m_out);
  libusb_exit(m_ctx);
  sem_destroy(&m_wake);
}

bool UsbRig::poll(double, DeviceSample& out) noexcept {
  const std::uint64_t v = m_latest.version();
  if (v == m_polled_version) return false;
  DeviceSample s;
  if (!m_latest.try_load(s)) return false;  // raced a write: take it next tick
  m_polled_version = v;
  out = s;
  return true;
}

void UsbRig::command(const DeviceCommand& c) noexcept {
  WireCommand w;
  w.state_sequence = c.state_sequence;
  w.enable = c.enable ? 1u : 0u;
  w.effort = c.effort;
  m_command.store(w);
  sem_post(&m_wake);
}

UsbRigCounters UsbRig::counters() const noexcept {
  UsbRigCounters c;
  c.packets = m_n.packets.load();
  c.lost = m_n.lost.load();
  c.too_short = m_n.too_short.load();
  c.too_long = m_n.too_long.load();
  c.bad_checksum = m_n.bad_checksum.load();
  c.bad_type_version = m_n.bad_type_version.load();
  c.stalls = m_n.stalls.load();
  c.transfer_errors = m_n.transfer_errors.load();
  c.commands_sent = m_n.commands_sent.load();
  c.commands_dropped = m_n.commands_dropped.load();
  c.connects = m_n.connects.load();
  c.disconnects = m_n.disconnects.load();
  return c;
}

void UsbRig::on_state_packet(const std::uint8_t* data, int length) noexcept {
  StatePacket p;
  const DecodeError e =
      decode_state(std::span<const std::uint8_t>(data, static_cast<std::size_t>(length)), p);
  switch (e) {
    case DecodeError::kOk:
      break;
    case DecodeError::kTooShort:
      ++m_n.too_short;
      return;
    case DecodeError::kTooLong:
      ++m_n.too_long;
      return;
    case DecodeError::kBadChecksum:
      ++m_n.bad_checksum;
      return;
    default:
      ++m_n.bad_type_version;
      return;
  }
  if (m_have_seq && p.sequence != m_last_seq + 1) m_n.lost += p.sequence - m_last_seq - 1;
  m_have_seq = true;
  m_last_seq = p.sequence;
  ++m_n.packets;
  DeviceSample s;
  s.sequence = p.sequence;
  s.time_s = monotonic_s();
  s.status = p.status;
  for (std::size_t h = 0; h < kHandles; ++h) {
    s.joints[h] = to_joints(m_c.calibration, p.handles[h]);
    s.pose[h] = forward(m_c.trocars[h], s.joints[h]);
    s.buttons[h] = p.handles[h].buttons;
  }
  m_latest.store(s);
}

void UsbRig::in_callback(libusb_transfer* t) {
  auto* self = static_cast<UsbRig*>(t->user_data);
  switch (t->status) {
    case LIBUSB_TRANSFER_COMPLETED:
      self->on_state_packet(t->buffer, t->actual_length);
      break;
    case LIBUSB_TRANSFER_STALL:
      ++self->m_n.stalls;
      libusb_clear_halt(t->dev_handle, kRigStateEndpoint);
      break;
    case LIBUSB_TRANSFER_NO_DEVICE:
      self->m_connected.store(false, std::memory_order_release);
      self->m_left.store(true);
      break;
    case LIBUSB_TRANSFER_CANCELLED:
      break;
    default:
      ++self->m_n.transfer_errors;
      break;
  }
  if (t->status != LIBUSB_TRANSFER_CANCELLED && t->status != LIBUSB_TRANSFER_NO_DEVICE &&
      !self->m_closing.load() && libusb_submit_transfer(t) == 0) {
    return;  // still in flight
  }
  if (t->status != LIBUSB_TRANSFER_CANCELLED && t->status != LIBUSB_TRANSFER_NO_DEVICE &&
      !self->m_closing.load()) {
    // Resubmission failed: the device is most likely gone.
    self->m_connected.store(false, std::memory_order_release);
    self->m_left.store(true);
  }
  self->m_in_flight.fetch_sub(1);
}

void UsbRig::out_callback(libusb_transfer* t) {
  auto* self = static_cast<UsbRig*>(t->user_data);
  if (t->status == LIBUSB_TRANSFER_NO_DEVICE) {
    self->m_connected.store(false, std::memory_order_release);
    self->m_left.store(true);
  }
  self->m_out_busy.store(false, std::memory_order_release);
}

bool rig_plugged_in(std::uint16_t vendor_id, std::uint16_t product_id) {
  libusb_context* ctx = nullptr;
  if (libusb_init(&ctx) != 0) return false;
  libusb_device** list = nullptr;
  const ssize_t n = libusb_get_device_list(ctx, &list);
  bool found = false;
  for (ssize_t i = 0; i < n && !found; ++i) {
    libusb_device_descriptor d{};
    found = libusb_get_device_descriptor(list[i], &d) == 0 && d.idVendor == vendor_id &&
            d.idProduct == product_id;
  }
  if (n >= 0) libusb_free_device_list(list, 1);
  libusb_exit(ctx);
  return found;
}

bool UsbRig::try_open() {
  libusb_device_handle* h = libusb_open_device_with_vid_pid(m_ctx, m_c.vendor_id, m_c.product_id);
  if (!h) return false;
  libusb_set_auto_detach_kernel_driver(h, 1);
  const int rc = libusb_claim_interface(h, kRigInterface);
  if (rc != 0) {
    spdlog::warn("usb rig: claiming interface {} failed: {}", kRigInterface, libusb_error_name(rc));
    libusb_close(h);
    return false;
  }
  m_handle = h;
  m_have_seq = false;
  int submit_error = 0;
  // Fresh transfers for each session: after a disconnect libusb may still flag the old ones.
  for (auto& t : m_in) {
    libusb_free_transfer(t);
    t = libusb_alloc_transfer(0);
  }
  {
    std::lock_guard<std::mutex> lock(m_out_mutex);
    libusb_free_transfer(m_out);
    m_out = libusb_alloc_transfer(0);
  }
  m_closing.store(false);
  for (int i = 0; i < kInTransfers; ++i) {
    libusb_fill_interrupt_transfer(m_in[i], h, kRigStateEndpoint, m_in_buf[i].data(),
                                   static_cast<int>(m_in_buf[i].size()), &UsbRig::in_callback, this,
                                   0);
    const int sr = libusb_submit_transfer(m_in[i]);
    if (sr == 0) {
      m_in_flight.fetch_add(1);
    } else {
      submit_error = sr;
    }
  }
  if (m_in_flight.load() == 0) {
    spdlog::warn("usb rig: opened but no IN transfer could be submitted: {}",
                 libusb_error_name(submit_error));
    close_device();
    return false;
  }
  ++m_n.connects;
  m_connected.store(true, std::memory_order_release);
  spdlog::info("usb rig: {:04x}:{:04x} opened", m_c.vendor_id, m_c.product_id);
  return true;
}

void UsbRig::close_device() {
  m_connected.store(false, std::memory_order_release);
  if (!m_handle) return;
  m_closing.store(true);
  { std::lock_guard<std::mutex> lock(m_out_mutex); }  // a submit in progress has finished
  for (auto* t : m_in) libusb_cancel_transfer(t);
  libusb_cancel_transfer(m_out);
  // Let the cancelled transfers complete before the handle goes (bounded wait).
  for (int i = 0; i < 200 && (m_in_flight.load() > 0 || m_out_busy.load()); ++i) {
    timeval tv{0, 5000};
    libusb_handle_events_timeout_completed(m_ctx, &tv, nullptr);
  }
  m_in_flight.store(0);
  m_out_busy.store(false);
  libusb_release_interface(m_handle, kRigInterface);
  libusb_close(m_handle);
  m_handle = nullptr;
  spdlog::info("usb rig: closed");
}

void UsbRig::event_thread() {
  double last_try = -1e9;
  while (!m_stop.load()) {
    if (m_left.exchange(false) && m_handle) {
      ++m_n.disconnects;
      m_connected.store(false, std::memory_order_release);
      close_device();
    }
    if (!m_handle) {
      const double now = monotonic_s();
      if (m_arrived.exchange(false) || now - last_try >= m_c.reopen_s) {
        last_try = now;
        try_open();
      }
    }
    timeval tv{0, 10000};
    libusb_handle_events_timeout_completed(m_ctx, &tv, nullptr);
  }
  close_device();
}

void UsbRig::writer_thread() {
  while (!m_stop.load()) {
    timespec ts{};
    clock_gettime(CLOCK_REALTIME, &ts);
    ts.tv_nsec += 10'000'000;
    if (ts.tv_nsec >= 1'000'000'000) {
      ts.tv_nsec -= 1'000'000'000;
      ++ts.tv_sec;
    }
    sem_timedwait(&m_wake, &ts);
    while (sem_trywait(&m_wake) == 0) {  // coalesce: only the newest command matters
    }
    const std::uint64_t v = m_command.version();
    if (v == m_sent_version || m_stop.load()) continue;
    WireCommand w;
    if (!m_command.try_load(w)) continue;
    m_sent_version = v;
    std::lock_guard<std::mutex> lock(m_out_mutex);
    if (!m_connected.load(std::memory_order_acquire) || m_out_busy.load()) {
      ++m_n.commands_dropped;
      continue;
    }
    ForcePacket p;
    p.sequence = ++m_out_seq;
    p.state_sequence = static_cast<std::uint32_t>(w.state_sequence);
    p.flags = w.enable ? kForceEnable : 0;
    for (std::size_t h = 0; h < kHandles; ++h) p.handles[h] = to_wire(w.effort[h]);
    encode_force(p, std::span<std::uint8_t, kForcePacketSize>(m_out_buf));
    libusb_device_handle* h = m_handle;  // read racily; a stale handle fails with NO_DEVICE
    if (!h) {
      ++m_n.commands_dropped;
      continue;
    }
    libusb_fill_interrupt_transfer(m_out, h, kRigForceEndpoint, m_out_buf.data(),
                                   static_cast<int>(m_out_buf.size()), &UsbRig::out_callback, this,
                                   100);
    m_out_busy.store(true);
    if (libusb_submit_transfer(m_out) == 0) {
      ++m_n.commands_sent;
    } else {
      m_out_busy.store(false);
      ++m_n.commands_dropped;
    }
  }
}

}  // namespace serosa::haptics
