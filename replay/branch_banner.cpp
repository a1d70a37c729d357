#include "replay/branch_banner.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace serosa::replay {

namespace {

// "a", "a and b", "a, b and c".
std::string listed(const std::vector<std::string>& items) {
  std::string out;
  for (std::size_t k = 0; k < items.size(); ++k) {
    if (k > 0) out.append(k + 1 == items.size() ? " and " : ", ");
    out.append(items[k]);
  }
  return out;
}

// What the mouse drives: each hand's instrument (an empty hand said as such: X fills it), then
// the endoscope.
std::vector<std::string> mouse_driven(const Scene& scene, const MouseTakeover& takeover,
                                      std::size_t active_hand) {
  std::vector<std::string> out;
  const auto& hands = takeover.handle_tools();
  for (std::size_t h = 0; h < hands.size(); ++h) {
    const bool held = hands[h] && *hands[h] < scene.tools.size();
    std::string item = held ? scene.tools[*hands[h]].name : std::string("no instrument");
    item.append(h == 0 ? " (left" : " (right").append(h == active_hand ? ", active)" : ")");
    out.push_back(std::move(item));
  }
  if (const auto s = takeover.scope_tool(); s && *s < scene.tools.size())
    out.push_back(scene.tools[*s].name + " (right button)");
  return out;
}

}  // namespace

std::string clock_time(double t_s) {
  const long long tenths = std::isfinite(t_s) ? std::llround(std::max(t_s, 0.0) * 10.0) : 0;
  char buf[40];
  std::snprintf(buf, sizeof buf, "%lld:%02lld.%lld", tenths / 600, (tenths % 600) / 10,
                tenths % 10);
  return buf;
}

std::string branch_banner(const Scene& scene, const MouseTakeover& takeover,
                          const BranchBannerInfo& info) {
  std::string out("BRANCH at ");
  out.append(clock_time(static_cast<double>(info.branch_step) * info.dt_s))
      .append(" (step ")
      .append(std::to_string(info.branch_step))
      .append("): the mouse drives ");
  const std::vector<std::string> mouse = mouse_driven(scene, takeover, info.active_hand);
  out.append(listed(mouse));
  std::vector<std::string> left;
  for (std::size_t i : takeover.left_tools())
    if (i < scene.tools.size()) left.push_back(scene.tools[i].name);
  if (!left.empty())
    out.append("; ")
        .append(listed(left))
        .append(left.size() == 1 ? " stays" : " stay")
        .append(" where the mouse left ")
        .append(left.size() == 1 ? "it" : "them");
  // The rest: every tool neither the mouse drives nor a hand let go of.
  std::size_t driven = left.size() + (takeover.scope_tool() ? 1 : 0);
  for (const auto& h : takeover.handle_tools()) driven += h ? 1 : 0;
  const std::size_t others = scene.tools.size() - std::min(scene.tools.size(), driven);
  if (others > 0)
    out.append(info.recording_plays ? "; the recording drives the rest"
                                    : "; the rest hold the recording's last pose");
  out.append(". Tab: other hand, X: next instrument");
  return out;
}

}  // namespace serosa::replay
