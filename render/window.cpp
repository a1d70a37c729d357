#include "render/window.h"

#include <epoxy/gl.h>
// epoxy before GLFW, so GLFW includes no GL header of its own.
#include <GLFW/glfw3.h>

#include <cstring>
#include <stdexcept>
#include <vector>

namespace serosa::render {
namespace {

int glfw_key(Key k) {
  switch (k) {
    case Key::kEscape:
      return GLFW_KEY_ESCAPE;
    case Key::kSpace:
      return GLFW_KEY_SPACE;
    case Key::kV:
      return GLFW_KEY_V;
    case Key::kUp:
      return GLFW_KEY_UP;
    case Key::kDown:
      return GLFW_KEY_DOWN;
    case Key::kO:
      return GLFW_KEY_O;
    case Key::kH:
      return GLFW_KEY_H;
    case Key::kLeft:
      return GLFW_KEY_LEFT;
    case Key::kRight:
      return GLFW_KEY_RIGHT;
    case Key::kPlus:
      return GLFW_KEY_EQUAL;  // '+' shares the '=' key on US layouts
    case Key::kMinus:
      return GLFW_KEY_MINUS;
    case Key::kTab:
      return GLFW_KEY_TAB;
    case Key::kW:
      return GLFW_KEY_W;
    case Key::kS:
      return GLFW_KEY_S;
    case Key::kQ:
      return GLFW_KEY_Q;
    case Key::kE:
      return GLFW_KEY_E;
    case Key::kJ:
      return GLFW_KEY_J;
    case Key::kB:
      return GLFW_KEY_B;
    case Key::kI:
      return GLFW_KEY_I;
    case Key::kK:
      return GLFW_KEY_K;
    case Key::kComma:
      return GLFW_KEY_COMMA;
    case Key::kPeriod:
      return GLFW_KEY_PERIOD;
    case Key::kN:
      return GLFW_KEY_N;
    case Key::kP:
      return GLFW_KEY_P;
    case Key::kF1:
      return GLFW_KEY_F1;
    case Key::kF2:
      return GLFW_KEY_F2;
    case Key::kHome:
      return GLFW_KEY_HOME;
    case Key::kX:
      return GLFW_KEY_X;
    case Key::kCount:
      break;
  }
  return GLFW_KEY_UNKNOWN;
}

// The keypad's twin of a key (plus and minus), else GLFW_KEY_UNKNOWN.
int keypad_key(Key k) {
  return k == Key::kPlus    ? GLFW_KEY_KP_ADD
         : k == Key::kMinus ? GLFW_KEY_KP_SUBTRACT
                            : GLFW_KEY_UNKNOWN;
}

}  // namespace

Window::Window(int width, int height, const std::string& title) {
  if (glfwInit() != GLFW_TRUE) {
    const char* msg = nullptr;
    glfwGetError(&msg);
    throw std::runtime_error(std::string("no window: GLFW could not start (") +
                             (msg ? msg : "no display?") + ")");
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 1);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  // Single-sampled: the visual view is drawn into the endoscope optic's own target and
  // anti-aliased there (render/lens_pass.h); multisampling the window only multiplied the cost of
  // that last pass (4 ms a frame at 640 x 480 on llvmpipe).
  glfwWindowHint(GLFW_SAMPLES, 0);
  m_window = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (m_window == nullptr) {
    const char* msg = nullptr;
    glfwGetError(&msg);
    glfwTerminate();
    throw std::runtime_error(std::string("no window: no OpenGL 4.1 core context (") +
                             (msg ? msg : "unknown GLFW error") + ")");
  }
  glfwMakeContextCurrent(m_window);
  // A key tapped between two frames (a slow frame, a quick finger) still counts as pressed once.
  glfwSetInputMode(m_window, GLFW_STICKY_KEYS, GLFW_TRUE);
  glfwSwapInterval(1);
  glfwSetWindowUserPointer(m_window, this);
  glfwGetCursorPos(m_window, &m_cursor_x, &m_cursor_y);
  glfwSetKeyCallback(m_window, on_key);
  glfwSetCursorPosCallback(m_window, on_cursor);
  glfwSetMouseButtonCallback(m_window, on_button);
  glfwSetScrollCallback(m_window, on_scroll);
}

void Window::on_key(GLFWwindow* w, int key, int /*scancode*/, int action, int /*mods*/) {
  if (action == GLFW_REPEAT) return;
  auto* self = static_cast<Window*>(glfwGetWindowUserPointer(w));
  for (int k = 0; k < static_cast<int>(Key::kCount); ++k) {
    if (glfw_key(static_cast<Key>(k)) != key && keypad_key(static_cast<Key>(k)) != key) continue;
    const auto i = static_cast<std::size_t>(k);
    if (action == GLFW_PRESS) {
      ++self->m_taps[i];
      ++self->m_events.presses[i];
      self->m_keys.press(i);
    } else if (const double held = self->m_keys.release(i); held >= 0.0) {
      self->m_events.released_after_s[i] = held;
    }
  }
}

void Window::on_cursor(GLFWwindow* w, double x, double y) {
  auto* self = static_cast<Window*>(glfwGetWindowUserPointer(w));
  if (self->m_left_held) {
    int ww = 0, wh = 0, fw = 0, fh = 0;
    glfwGetWindowSize(w, &ww, &wh);
    glfwGetFramebufferSize(w, &fw, &fh);
    const double sx = ww > 0 ? static_cast<double>(fw) / ww : 1.0;
    const double sy = wh > 0 ? static_cast<double>(fh) / wh : 1.0;
    self->m_events.drag_dx_px += static_cast<float>((x - self->m_cursor_x) * sx);
    self->m_events.drag_dy_px += static_cast<float>((y - self->m_cursor_y) * sy);
  }
  self->m_cursor_x = x;
  self->m_cursor_y = y;
}

void Window::on_button(GLFWwindow* w, int button, int action, int /*mods*/) {
  auto* self = static_cast<Window*>(glfwGetWindowUserPointer(w));
  if (button != GLFW_MOUSE_BUTTON_LEFT) return;
  // The drag starts where the last motion event left the pointer, not where glfwGetCursorPos
  // says it is now: events still queued behind a slow frame would otherwise be measured from a
  // later position, and a quick drag would lose all but its last moves.
  self->m_left_held = action == GLFW_PRESS;
}

void Window::on_scroll(GLFWwindow* w, double /*dx*/, double dy) {
  auto* self = static_cast<Window*>(glfwGetWindowUserPointer(w));
  self->m_events.scroll_steps += static_cast<float>(dy);
}

Window::Events Window::take_events() {
  Events e = m_events;
  m_events = Events{};
  return e;
}

bool Window::key_down(Key key) const {
  return key != Key::kCount && glfwGetKey(m_window, glfw_key(key)) == GLFW_PRESS;
}

double Window::key_held_s(Key key) const {
  return m_keys.held_s(static_cast<std::size_t>(key), glfwGetTime());
}

Window::~Window() {
  if (m_window != nullptr) glfwDestroyWindow(m_window);
  glfwTerminate();
}

bool Window::should_close() const { return glfwWindowShouldClose(m_window) != 0; }
void Window::close() { glfwSetWindowShouldClose(m_window, GLFW_TRUE); }
void Window::poll_events() {
  m_keys.poll(glfwGetTime());
  glfwPollEvents();
}
void Window::swap_buffers() { glfwSwapBuffers(m_window); }

void Window::bind_framebuffer() {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glViewport(0, 0, width(), height());
}

int Window::width() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(m_window, &w, &h);
  return w;
}

int Window::height() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(m_window, &w, &h);
  return h;
}

bool Window::pressed(Key key) {
  if (key == Key::kCount) return false;
  // Counted by the key callback, not read from the key's state: a second tap that came and went
  // before the next poll would read as the same press.
  int& taps = m_taps[static_cast<std::size_t>(key)];
  if (taps == 0) return false;
  --taps;
  return true;
}

void Window::cursor(float& x, float& y) const {
  double cx = 0.0;
  double cy = 0.0;
  glfwGetCursorPos(m_window, &cx, &cy);
  int ww = 0, wh = 0, fw = 0, fh = 0;
  glfwGetWindowSize(m_window, &ww, &wh);
  glfwGetFramebufferSize(m_window, &fw, &fh);
  // Window coordinates to framebuffer pixels (they differ on high-DPI screens).
  const double sx = ww > 0 ? static_cast<double>(fw) / ww : 1.0;
  const double sy = wh > 0 ? static_cast<double>(fh) / wh : 1.0;
  x = static_cast<float>(cx * sx);
  y = static_cast<float>(cy * sy);
}

bool Window::mouse_down() const {
  return glfwGetMouseButton(m_window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
}

bool Window::right_mouse_down() const {
  return glfwGetMouseButton(m_window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
}

Image Window::read_image() {
  Image img;
  img.width = width();
  img.height = height();
  const std::size_t row = 4 * static_cast<std::size_t>(img.width);
  std::vector<std::uint8_t> bottom_up(row * static_cast<std::size_t>(img.height));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, img.width, img.height, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());
  img.rgba.resize(bottom_up.size());
  for (std::size_t y = 0; y < static_cast<std::size_t>(img.height); ++y) {
    std::memcpy(img.rgba.data() + y * row,
                bottom_up.data() + (static_cast<std::size_t>(img.height) - 1 - y) * row, row);
  }
  return img;
}

void Window::set_title(const std::string& title) { glfwSetWindowTitle(m_window, title.c_str()); }

}  // namespace serosa::render
