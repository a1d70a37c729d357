#include "haptics/emulated_hands.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "engine/input_error.h"

namespace serosa::haptics {
namespace {

const char* hand_name(std::size_t h) { return h == 0 ? "left" : "right"; }

std::string seconds(double t) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f s", t);
  return buf;
}

// The rack's instrument that scene tool `name` is, if any.
std::optional<std::size_t> rack_index(const Scene& scene, const HandRack& rack,
                                      const std::string& name) {
  for (std::size_t k = 0; k < rack.instruments().size(); ++k)
    if (scene.tools[rack.instruments()[k].tool].name == name) return k;
  return std::nullopt;
}

std::string rack_names(const Scene& scene, const HandRack& rack) {
  std::string out;
  for (const RackInstrument& r : rack.instruments())
    out += (out.empty() ? "" : ", ") + scene.tools[r.tool].name;
  return out;
}

struct Event {
  double t_s;
  std::size_t hand;
  HandChange change;
};

// Plays every exchange of both hands in time order on a copy of the rack: each must bring in the
// instrument the hand column names.
void check_order(const Scene& scene, const HandRack& rack, const ToolPath& path,
                 const std::array<std::optional<RigHand>, kHandles>& hands) {
  std::vector<Event> events;
  for (std::size_t h = 0; h < kHandles; ++h)
    if (hands[h])
      for (const HandChange& c : hands[h]->exchanges) events.push_back({c.t_s, h, c});
  std::stable_sort(events.begin(), events.end(),
                   [](const Event& a, const Event& b) { return a.t_s < b.t_s; });
  HandRack play = rack;
  for (const Event& e : events) {
    const std::string& want = path.tools[e.change.tool];
    const std::optional<std::size_t> had = play.held(e.hand);
    const std::optional<std::size_t> got = play.exchange(e.hand);
    const std::string got_name = got ? scene.tools[rack.instruments()[*got].tool].name : "none";
    if (got_name == want) continue;
    const std::string had_name = had ? scene.tools[rack.instruments()[*had].tool].name : "none";
    throw InputError(path.file, 0,
                     "the " + std::string(hand_name(e.hand)) + " hand takes '" + want + "' at " +
                         seconds(e.t_s) + ", but an exchange there brings in '" + got_name +
                         "' (the next waiting after '" + had_name + "' in scene order)",
                     "the scene's instruments listed in the order the hands take them");
  }
}

}  // namespace

std::array<std::optional<RigHand>, kHandles> emulated_hands(const Scene& scene,
                                                            const HandRack& rack,
                                                            const ToolPath& path) {
  std::array<std::optional<RigHand>, kHandles> hands{};
  for (std::size_t h = 0; h < kHandles; ++h) {
    const std::optional<std::size_t> first = rack.held(h);
    if (!first) continue;
    const std::string& first_name = scene.tools[rack.instruments()[*first].tool].name;
    std::vector<TrocarMap> to_handle(path.tools.size());
    for (std::size_t k = 0; k < path.tools.size(); ++k)
      if (const auto r = rack_index(scene, rack, path.tools[k]))
        to_handle[k] = trocar_map(rack.instruments()[*r].trocar, rack.handle_trocar(h));
    const Hand hand = h == 0 ? Hand::kLeft : Hand::kRight;
    RigHand plan = plan_rig_hand(path, hand, path.index_of(first_name), rack.handle_trocar(h),
                                 std::move(to_handle));
    for (const HandChange& c : plan.exchanges)
      if (!rack_index(scene, rack, path.tools[c.tool]))
        throw InputError(path.file, 0,
                         "the " + std::string(hand_name(h)) + " hand takes '" + path.tools[c.tool] +
                             "' at " + seconds(c.t_s) +
                             ", which is not one of the rig's instruments",
                         "one of: " + rack_names(scene, rack));
    hands[h] = std::move(plan);
  }
  check_order(scene, rack, path, hands);
  return hands;
}

}  // namespace serosa::haptics
