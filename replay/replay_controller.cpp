#include "replay/replay_controller.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <spdlog/spdlog.h>

#include "app/compose.h"
#include "app/simulation.h"
#include "engine/input_error.h"
#include "recording/record_stage.h"
#include "replay/old_snapshots.h"
#include "replay/recorded_scene.h"

namespace serosa::replay {

using namespace serosa::app;  // the driver, the composition and the window's parts

ReplayController::ReplayController(const std::filesystem::path& recording,
                                   ReplayControllerOptions options)
    : m_rec(recording::read_recording(recording)), m_options(options), m_path(recording) {
  const std::string file = recording.string();
  if (const auto old = drop_old_snapshots(m_rec, file)) spdlog::warn("{}", old->text);
  m_scene = recorded_scene(m_rec, file);
  if (!(options.snapshot_every_s > 0.0))
    throw InputError("snapshot_every_s", 0, "not positive", "> 0 s");
  m_snapshot_every = std::max<std::uint64_t>(
      1, static_cast<std::uint64_t>(std::llround(options.snapshot_every_s / dt_s())));
  set_speed(options.speed);
  // The recording's own snapshots, with the hash of the step before each where one was recorded.
  for (const auto& [steps, bytes] : m_rec.snapshots) {
    if (steps == 0 || steps > num_steps()) continue;
    const auto h = m_rec.hashes.find(steps - 1);
    m_snapshots.try_emplace(
        steps, Snapshot{bytes, h == m_rec.hashes.end() ? std::nullopt
                                                       : std::optional<std::uint64_t>(h->second)});
  }
  restart(nullptr);
}

ReplayController::~ReplayController() = default;

// A whole-state snapshot restores every stage's part too: the run goes on as recorded.
void ReplayController::restart(const Snapshot* from) {
  if (!m_sim) {
    HeadlessOptions o;
    o.steps = static_cast<std::int64_t>(num_steps());
    o.progress = false;
    o.scene_record = false;
    m_sim = std::make_unique<Simulation>(m_scene, o, hooks());
  } else if (from == nullptr) {
    m_sim->reset();
  } else {
    m_sim->restore(from->bytes, m_path.string() + ": snapshot");
  }
  m_stages = m_next;  // the pipeline built last is in use (a restore that threw kept the old)
  if (from != nullptr) m_stages.hash->set_last_hash(from->hash);
  ++m_restarts;
  m_exact = true;
}

SimulationHooks ReplayController::hooks() {
  SimulationHooks h;
  h.tool_input = [this] {
    auto input = std::make_unique<ReplayInputStage>(m_rec.inputs);
    m_next.input = input.get();
    return input;
  };
  h.extend = [this](Runner& runner) {
    auto record = std::make_unique<RecordStage>(nullptr, m_scene.record.hash_every);
    m_next.record = record.get();
    runner.add(Slot::record, std::move(record));
    auto hash = std::make_unique<VerifyStage>(m_rec.hashes, /*every_step=*/true);
    m_next.hash = hash.get();
    runner.add(Slot::record, std::move(hash));
  };
  h.quiet = true;  // the recorded run said what there was to say of its scene
  return h;
}

void ReplayController::set_speed(double speed) {
  m_speed = std::clamp(std::isfinite(speed) ? speed : 1.0, kMinSpeed, kMaxSpeed);
}

bool ReplayController::step_forward() {
  if (at_end()) return false;
  const SimState& s = m_sim->state();
  if (m_branch_step) feed_recorded_inputs();
  m_sim->step();
  if (m_branch_step) {
    record_branch_snapshot_if_due();
    return true;
  }
  if (s.step % m_snapshot_every == 0 && m_exact && s.events.cuts.empty() &&
      !m_snapshots.contains(s.step))
    m_snapshots.emplace(s.step, Snapshot{m_sim->snapshot(), last_step_hash()});
  return true;
}

// The tools no one took over go on as recorded; past the recording's end they keep its last input.
void ReplayController::feed_recorded_inputs() {
  const std::uint64_t k = steps_taken();
  if (k >= num_steps()) return;
  const std::vector<ToolState>& recorded = m_rec.inputs[k];
  for (std::size_t i = 0; i < m_driven.size() && i < recorded.size(); ++i)
    if (!m_driven[i]) m_stages.input->set_live(i, recorded[i]);
}

// As Runner::record_snapshots: at the first step on or after each multiple of the cadence that has
// no cut in flight (the FEM stage takes a step's cuts at the next one).
void ReplayController::record_branch_snapshot_if_due() {
  const SimState& s = m_sim->state();
  if (m_branch_closed || m_branch_snapshot_every == 0 || s.step < m_branch_next_snapshot ||
      !s.events.cuts.empty())
    return;
  m_branch_writer->record_snapshot(s.step, m_sim->snapshot());
  m_branch_next_snapshot = (s.step / m_branch_snapshot_every + 1) * m_branch_snapshot_every;
}

std::uint64_t ReplayController::advance(double wall_dt_s) {
  if (m_paused || at_end() || !(wall_dt_s > 0.0)) return 0;
  m_due += wall_dt_s * m_speed;
  std::uint64_t taken = 0;
  while (m_due >= dt_s() && step_forward()) {
    m_due -= dt_s();
    ++taken;
  }
  if (at_end()) m_due = 0.0;
  return taken;
}

void ReplayController::seek_step(std::uint64_t steps) {
  if (m_branch_step) return;  // a branch is a live run: it cannot be seeked
  steps = std::min(steps, num_steps());
  m_due = 0.0;
  if (steps < steps_taken()) {
    // The nearest snapshot at or before the target, else the start.
    const auto it = m_snapshots.upper_bound(steps);
    if (m_options.from_start || it == m_snapshots.begin()) {
      restart(nullptr);
    } else {
      const Snapshot from = std::prev(it)->second;
      restart(&from);
    }
  }
  while (steps_taken() < steps && step_forward()) {
  }
}

void ReplayController::seek(double t_s) {
  const double k = std::isfinite(t_s) ? std::round(std::max(t_s, 0.0) / dt_s()) : 0.0;
  seek_step(static_cast<std::uint64_t>(std::min(k, static_cast<double>(num_steps()))));
}

bool ReplayController::at_end() const {
  if (m_branch_step) return m_branch_closed;
  return steps_taken() >= num_steps();
}

void ReplayController::branch(const std::filesystem::path& branch_file) {
  if (m_branch_step) throw std::logic_error("this replay has already branched");
  if (!m_exact)
    throw std::logic_error("branching needs the exact recorded state: seek exactly first");
  const std::uint64_t k = steps_taken();
  recording::Header h = m_rec.header;
  h.set("parent", std::filesystem::absolute(m_path).lexically_normal().string());
  h.set("branch_step", std::to_string(k));
  h.set("steps_planned", "0");
  m_branch_writer = std::make_unique<recording::RecordingWriter>(branch_file, h);
  copy_prefix(k);
  m_branch_writer->record_event(k, "branch");
  // The branch's snapshots go on at the recording's cadence, from the parent's last one before it.
  m_branch_snapshot_every = static_cast<std::uint64_t>(
      std::max<long long>(0, std::llround(m_scene.record.snapshot_every_s / dt_s())));
  std::uint64_t last = 0;
  for (const auto& [steps, bytes] : m_rec.snapshots)
    if (steps <= k) last = steps;
  if (m_branch_snapshot_every > 0)
    m_branch_next_snapshot = (last / m_branch_snapshot_every + 1) * m_branch_snapshot_every;
  m_branch_step = k;
  m_exact = false;  // from here on the run is the branch, not the recording
  m_driven.assign(m_scene.tools.size(), false);
  m_stages.input->go_live(m_sim->state().tools);
  m_stages.record->attach(m_branch_writer.get());
}

// The parent's inputs, hashes and snapshots before step k, so that the branch replays from step 0
// and starts late from the parent's snapshots as well as its own.
void ReplayController::copy_prefix(std::uint64_t k) {
  for (std::uint64_t s = 0; s < k; ++s) {
    m_branch_writer->record_inputs(s, m_rec.inputs[s]);
    if (const auto it = m_rec.hashes.find(s); it != m_rec.hashes.end())
      m_branch_writer->record_hash(s, it->second);
    if (const auto it = m_rec.snapshots.find(s + 1); it != m_rec.snapshots.end())
      m_branch_writer->record_snapshot(s + 1, it->second);
  }
}

void ReplayController::set_tool_input(std::size_t i, const ToolState& input) {
  if (!m_branch_step || m_branch_closed) throw std::logic_error("not in a branch");
  m_stages.input->set_live(i, input);
  m_driven.at(i) = true;
}

bool ReplayController::recording_drives(std::size_t i) const {
  if (i >= m_scene.tools.size()) return false;
  return !m_branch_step || !m_driven[i];
}

void ReplayController::end_branch() {
  if (!m_branch_writer || m_branch_closed) return;
  m_stages.record->attach(nullptr);
  m_branch_writer->close(steps_taken());
  m_branch_closed = true;
}

std::uint64_t ReplayController::steps_taken() const { return m_sim->state().step; }
double ReplayController::time_s() const { return m_sim->state().time_s; }
std::optional<std::uint64_t> ReplayController::last_step_hash() const {
  return m_stages.hash->last_hash();
}
std::uint64_t ReplayController::hashes_checked() const { return m_stages.hash->checked(); }
std::optional<std::uint64_t> ReplayController::diverged_at() const {
  const auto& d = m_stages.hash->divergence();
  return d ? std::optional<std::uint64_t>(d->step) : std::nullopt;
}
const SimState& ReplayController::state() const { return m_sim->state(); }
const Composition& ReplayController::composition() const { return m_sim->composition(); }
std::map<int, std::string> ReplayController::group_names() const {
  return m_sim->assembled().group_names();
}

}  // namespace serosa::replay
