#include "engine/runner.h"

#include <algorithm>
#include <cstring>
#include <map>
#include <stdexcept>

#include "engine/input_error.h"
#include "engine/sim_state.h"
#include "engine/state_codec.h"
#include "engine/state_walk.h"

namespace serosa {

Runner::Runner(double dt_s) : m_dt_s(dt_s) {
  if (!(dt_s > 0.0)) throw std::invalid_argument("Runner: dt must be > 0");
}

void Runner::add(Slot slot, std::unique_ptr<Stage> stage) {
  if (!stage) throw std::invalid_argument("Runner: null stage");
  const auto after = std::upper_bound(m_entries.begin(), m_entries.end(), slot,
                                      [](Slot s, const Entry& e) { return s < e.slot; });
  StageTiming timing{std::string(stage->name()), 0.0, 0, 0.0};
  m_entries.insert(after, Entry{slot, std::move(stage), std::move(timing)});
}

void Runner::run_slot(Slot slot, const StepContext& ctx, SimState& state) {
  for (Entry& e : m_entries) {
    if (e.slot != slot) continue;
    const auto t0 = std::chrono::steady_clock::now();
    e.stage->step(ctx, state);
    e.timing.last_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    e.timing.total_s += e.timing.last_s;
    ++e.timing.calls;
  }
}

// The whole solver step, in order. Each place reads what the earlier ones handed on in
// SimState::shared and writes its own part (engine/sim_state.h).
void Runner::step(SimState& state) {
  const StepContext ctx{state.step, state.time_s, m_dt_s};
  run_slot(Slot::tools, ctx, state);
  run_slot(Slot::haptics, ctx, state);
  run_slot(Slot::contact, ctx, state);
  run_slot(Slot::fem, ctx, state);
  run_slot(Slot::cutting, ctx, state);
  run_slot(Slot::surface, ctx, state);
  run_slot(Slot::metrics, ctx, state);
  run_slot(Slot::record, ctx, state);
  ++state.step;
  // Time from the step count, not by accumulation, so long runs do not drift.
  state.time_s = static_cast<double>(state.step) * m_dt_s;
  record_snapshot_if_due(state);
}

namespace {
constexpr char kSnapshotMagic[4] = {'S', 'N', 'A', 'P'};
constexpr std::uint32_t kSnapshotVersion = 6;
}  // namespace

// A snapshot waits for a step with no cut in flight (the FEM stage takes a step's cuts at the
// next one; the snapshot holds the state between steps).
void Runner::record_snapshot_if_due(const SimState& state) {
  if (m_snapshot_sink == nullptr || state.step < m_next_snapshot || !state.events.cuts.empty())
    return;
  m_snapshot_sink->record_snapshot(state.step, snapshot(state));
  m_next_snapshot = (state.step / m_snapshot_every + 1) * m_snapshot_every;
}

void Runner::record_snapshots(SnapshotSink& sink, std::uint64_t every_steps) {
  m_snapshot_sink = every_steps > 0 ? &sink : nullptr;
  m_snapshot_every = every_steps;
  m_next_snapshot = every_steps;
}

std::vector<std::uint8_t> Runner::snapshot(const SimState& state) const {
  StateWriter out;
  out.raw(kSnapshotMagic, sizeof kSnapshotMagic);
  out.u32(kSnapshotVersion);
  write_sim_state(out, state);
  std::vector<std::pair<std::string, StateWriter>> blocks;
  StageBlocks::each_named(state.blocks, [&](const char* name, const auto& block) {
    StateWriter w;
    put(w, block);
    blocks.emplace_back(name, std::move(w));
  });
  out.u32(static_cast<std::uint32_t>(blocks.size()));
  for (auto& [name, block] : blocks) {
    out.string(name);
    out.u64(block.size());
    out.raw(block.bytes().data(), block.size());
  }
  return std::move(out.bytes());
}

std::uint32_t snapshot_version() noexcept { return kSnapshotVersion; }

std::uint32_t snapshot_version(std::span<const std::uint8_t> snapshot) noexcept {
  std::uint32_t v = 0;
  if (snapshot.size() < sizeof kSnapshotMagic + sizeof v ||
      std::memcmp(snapshot.data(), kSnapshotMagic, sizeof kSnapshotMagic) != 0)
    return 0;
  std::memcpy(&v, snapshot.data() + sizeof kSnapshotMagic, sizeof v);
  return v;
}

std::vector<SnapshotSection> snapshot_sections(std::span<const std::uint8_t> snapshot,
                                               const std::string& what) {
  StateReader in(snapshot, what);
  char magic[4] = {};
  in.raw(magic, sizeof magic);
  if (std::memcmp(magic, kSnapshotMagic, sizeof magic) != 0) in.fail("not a snapshot (magic)");
  if (const std::uint32_t v = in.u32(); v != kSnapshotVersion)
    in.fail("snapshot version " + std::to_string(v) + ", this build reads " +
            std::to_string(kSnapshotVersion));
  std::vector<SnapshotSection> sections;
  const std::size_t begin = in.offset();
  (void)read_sim_state(in);
  sections.push_back({"state", begin, in.offset() - begin});
  const std::uint32_t n = in.u32();
  for (std::uint32_t i = 0; i < n; ++i) {
    std::string name = in.string();
    const std::uint64_t len = in.u64();
    if (len > in.left()) in.fail("stage '" + name + "': block runs past the end");
    sections.push_back({std::move(name), in.offset(), static_cast<std::size_t>(len)});
    (void)in.view(static_cast<std::size_t>(len));
  }
  if (in.left() != 0) in.fail("bytes after the last block");
  return sections;
}

void Runner::restore(std::span<const std::uint8_t> snapshot, SimState& state,
                     const std::string& what) {
  const std::vector<SnapshotSection> sections = snapshot_sections(snapshot, what);
  StateReader sim(snapshot.subspan(sections.front().offset, sections.front().size), what);
  SimState restored = read_sim_state(sim);
  std::map<std::string, std::span<const std::uint8_t>> blocks;
  for (std::size_t i = 1; i < sections.size(); ++i)
    blocks[sections[i].name] = snapshot.subspan(sections[i].offset, sections[i].size);
  StageBlocks::each_named(restored.blocks, [&](const char* name, auto& block) {
    const auto it = blocks.find(name);
    if (it == blocks.end())
      throw InputError(what, 0, std::string("the snapshot has no block '") + name + "'");
    StateReader in(it->second, what + ": block '" + name + "'");
    get(in, block);
    if (in.left() != 0) in.fail("bytes after the block's last field");
    blocks.erase(it);
  });
  if (!blocks.empty())
    throw InputError(what, 0, "a block this build does not know: '" + blocks.begin()->first + "'");
  state = std::move(restored);
  for (Entry& e : m_entries) {
    try {
      e.stage->adopt(state);
    } catch (const BlockMismatch& m) {
      throw InputError(what + ": block '" + std::string(e.stage->name()) + "'", 0, m.what());
    }
  }
}

void Runner::prepare(SimState& state) {
  const StepContext ctx{state.step, state.time_s, m_dt_s};
  for (Entry& e : m_entries) e.stage->prepare(ctx, state);
}

void Runner::run(SimState& state, std::uint64_t n) {
  for (std::uint64_t i = 0; i < n; ++i) step(state);
}

double Runner::last_stage_s(std::string_view name) const {
  double s = 0.0;
  for (const Entry& e : m_entries)
    if (e.timing.name == name) s += e.timing.last_s;
  return s;
}

std::vector<StageTiming> Runner::timings() const {
  std::vector<StageTiming> t;
  t.reserve(m_entries.size());
  for (const Entry& e : m_entries) t.push_back(e.timing);
  return t;
}

}  // namespace serosa
