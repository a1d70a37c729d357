#include "window/window_interrupt.h"

#include <csignal>

namespace serosa::window {
namespace {

// Set by the handler, read by the window loops (see the header for why it is process-wide).
std::atomic<bool> g_interrupted{false};
static_assert(std::atomic<bool>::is_always_lock_free);

extern "C" void on_interrupt(int /*signal*/) { g_interrupted.store(true); }

}  // namespace

InterruptGuard::InterruptGuard()
    : m_int((g_interrupted.store(false), std::signal(SIGINT, on_interrupt))),
      m_term(std::signal(SIGTERM, on_interrupt)) {}

InterruptGuard::~InterruptGuard() {
  std::signal(SIGINT, m_int == SIG_ERR ? SIG_DFL : m_int);
  std::signal(SIGTERM, m_term == SIG_ERR ? SIG_DFL : m_term);
}

bool InterruptGuard::interrupted() const { return g_interrupted.load(); }

const std::atomic<bool>& InterruptGuard::flag() const { return g_interrupted; }

}  // namespace serosa::window
