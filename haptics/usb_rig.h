// UsbRig: the libusb driver of the two-handle rig (docs/rig-protocol.md).
//
// Threads (none of them is the 1 kHz loop):
//   event thread   runs libusb_handle_events; keeps kInTransfers interrupt IN transfers queued on
//                  EP 0x81, decodes each state packet (strict: length, CRC, type, version) into a
//                  DeviceSample published through a Seqlock; handles stalls (clear halt),
//                  hotplug (arrive -> open and claim; leave or LIBUSB_TRANSFER_NO_DEVICE ->
//                  connected() false at once, transfers cancelled, handle closed) and retries
//                  opening every reopen_s while the rig is absent, so a replugged rig comes back
//                  without restarting the session.
//   writer thread  wakes on each command (a semaphore the loop posts: no lock), encodes the
//                  newest command and submits it as one interrupt OUT transfer on EP 0x01; if the
//                  previous one is still in flight the command is dropped (counted).
// The loop's side (poll, connected, command) never blocks, allocates or locks.
#pragma once

#include <semaphore.h>

#include <array>
#include <atomic>
#include <cstdint>
#include <mutex>
#include <thread>

#include "engine/seqlock.h"
#include "haptics/device.h"
#include "haptics/rig_calibration.h"

struct libusb_context;
struct libusb_device_handle;
struct libusb_transfer;

namespace serosa::haptics {

struct UsbRigConfig {
  std::uint16_t vendor_id = kRigVendorId;
  std::uint16_t product_id = kRigProductId;
  RigCalibration calibration{};
  std::array<Trocar, kHandles> trocars{};
  double reopen_s = 0.5;  ///< while absent, try to open this often (hotplug also triggers it)
};

/// Driver counters (monotonic; read any time).
struct UsbRigCounters {
  std::uint64_t packets = 0;    ///< valid state packets
  std::uint64_t lost = 0;       ///< sequence gaps (packets the device sent, host never saw)
  std::uint64_t too_short = 0;  ///< truncated packets
  std::uint64_t too_long = 0;
  std::uint64_t bad_checksum = 0;
  std::uint64_t bad_type_version = 0;  ///< wrong type, version or length field
  std::uint64_t stalls = 0;            ///< IN endpoint stalls (halt cleared, resubmitted)
  std::uint64_t transfer_errors = 0;   ///< other failed IN transfers
  std::uint64_t commands_sent = 0;     ///< force packets submitted
  std::uint64_t commands_dropped =
      0;                          ///< commands skipped: previous OUT still in flight, or absent
  std::uint64_t connects = 0;     ///< successful opens
  std::uint64_t disconnects = 0;  ///< unplugs seen
};

/// Whether a device with the rig's ids is on the USB bus now (a real rig, or the emulated one
/// under umockdev), enumerated through a libusb context of its own; false when libusb cannot
/// start. The session asks it once, to give the instruments to the rig or to the mouse.
[[nodiscard]] bool rig_plugged_in(std::uint16_t vendor_id = kRigVendorId,
                                  std::uint16_t product_id = kRigProductId);

class UsbRig final : public Device {
 public:
  static constexpr int kInTransfers = 4;

  /// Initializes libusb, registers hotplug and starts the threads. The rig may be absent: it is
  /// opened when it appears. Throws std::runtime_error when libusb cannot initialize.
  explicit UsbRig(const UsbRigConfig& c = {});
  ~UsbRig() override;

  bool poll(double now_s, DeviceSample& out) noexcept override;
  [[nodiscard]] bool connected() const noexcept override {
    return m_connected.load(std::memory_order_acquire);
  }
  void command(const DeviceCommand& c) noexcept override;
  [[nodiscard]] const char* name() const noexcept override { return "usb-rig"; }

  [[nodiscard]] UsbRigCounters counters() const noexcept;

 private:
  static void in_callback(libusb_transfer* t);
  static void out_callback(libusb_transfer* t);
  void event_thread();
  void writer_thread();
  bool try_open();
  void close_device();
  void on_state_packet(const std::uint8_t* data, int length) noexcept;

  UsbRigConfig m_c;
  libusb_context* m_ctx = nullptr;
  std::atomic<libusb_device_handle*> m_handle{nullptr};  // written by the event thread only
  int m_hotplug_handle = 0;
  bool m_hotplug = false;
  std::array<std::atomic<bool>*, 2> m_hotplug_flags{};  // arrived, left
  std::array<libusb_transfer*, kInTransfers> m_in{};
  std::array<std::array<std::uint8_t, 64>, kInTransfers> m_in_buf{};
  libusb_transfer* m_out = nullptr;
  std::array<std::uint8_t, kForcePacketSize> m_out_buf{};
  std::atomic<int> m_in_flight{0};
  std::atomic<bool> m_out_busy{false};

  std::atomic<bool> m_stop{false};
  std::atomic<bool> m_connected{false};
  std::atomic<bool> m_arrived{false};
  std::atomic<bool> m_left{false};
  std::atomic<bool> m_closing{false};
  std::thread m_events;
  std::thread m_writer;
  sem_t m_wake{};
  std::mutex m_out_mutex;  // writer vs close_device only (driver threads, never the loop)

  Seqlock<DeviceSample> m_latest{};
  std::uint64_t m_polled_version = 0;  // loop thread
  struct WireCommand {                 // the part of a DeviceCommand that goes on the wire
    std::uint64_t state_sequence = 0;
    std::uint32_t enable = 0;
    std::array<JointEffort, kHandles> effort{};
  };
  Seqlock<WireCommand> m_command{};
  std::uint64_t m_sent_version = 0;  // writer thread
  std::uint32_t m_out_seq = 0;       // writer thread
  bool m_have_seq = false;           // event thread
  std::uint32_t m_last_seq = 0;      // event thread

  struct AtomicCounters {
    std::atomic<std::uint64_t> packets{0}, lost{0}, too_short{0}, too_long{0}, bad_checksum{0},
        bad_type_version{0}, stalls{0}, transfer_errors{0}, commands_sent{0}, commands_dropped{0},
        connects{0}, disconnects{0};
  } m_n;
};

}  // namespace serosa::haptics
