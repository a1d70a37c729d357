// serosa replay REC.lapr [--headless] [--verify] [--from T] [--speed S] [--frames DIR]
//               [--report OUT.json]
//
// Without --headless: the instructor's replay in a window (app/session.h run_replay_window:
// pause, seek, speed). With --headless: re-simulates as fast as it can (replay/replay.h).
//
// --from T (headless): restore the last whole-state snapshot at or before T and replay from there
// (the report's start_step); without one that early, from step 0. A T past the recording's end
// warns (stderr and the report's "warnings") and starts from the last snapshot. stdout carries the
// report alone: logs and warnings go to stderr.
// Exit codes: 0 replayed (and, with --verify, every recorded hash and snapshot matched up to
// where the recording ends); 1 bad input (not a recording, damaged header, scene unreadable);
// 3 --verify found a divergence (the step, and for a snapshot the part, is named); 4 --verify on a
// corrupt recording (a checksum or record error before its end: replayed and verified up to there,
// then named). A recording merely cut short (crash, kill -9) replays up to its last chunk and exits
// 0.
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "app/camera_option.h"
#include "app/session.h"
#include "engine/input_error.h"
#include "replay/cmd_replay.h"
#include "replay/replay.h"
#include "replay/replay_window.h"

namespace serosa::replay {

using namespace serosa::app;  // the driver, the composition and the window's parts

void add_replay_command(CLI::App& app, app::Action& action) {
  auto opts = std::make_shared<ReplayOptions>();
  auto headless = std::make_shared<bool>(false);
  auto speed = std::make_shared<double>(1.0);
  auto frames = std::make_shared<std::string>();
  auto report = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("replay", "Replay a recorded run (.lapr)");
  cmd->add_option("recording", opts->recording, "Recording file (.lapr)")->required();
  cmd->add_flag("--headless", *headless, "Replay without a window, as fast as possible");
  cmd->add_flag("--verify", opts->verify,
                "Check every recorded state hash; exit 3 at the first divergence");
  auto from = std::make_shared<double>(-1.0);
  cmd->add_option("--from", *from,
                  "Headless: start at this time (s), from the last snapshot at or before it")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--speed", *speed, "Playback speed in a window (1 = real time)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--frames", *frames, "Write PNG pictures of the replay into this folder");
  add_camera_option(*cmd, opts->fitted_camera);
  cmd->add_option("--frame-count", opts->frame_count, "Pictures over the replay (with --frames)")
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--report", *report, "Write the JSON report here (also printed)");
  auto seconds = std::make_shared<double>(0.0);
  auto snapshot = std::make_shared<std::string>();
  cmd->add_option("--seconds", *seconds, "In a window: close after this much wall time (0: never)");
  cmd->add_option("--snapshot", *snapshot,
                  "In a window: also write the last picture drawn to this PNG");
  auto layout_log = std::make_shared<std::string>();
  cmd->add_option("--layout-log", *layout_log,
                  "In a window: with the last picture, write where the overlay's panels were and "
                  "what the debrief said to this JSON file (checks)");
  auto branch_at = std::make_shared<double>(-1.0);
  auto branch_file = std::make_shared<std::string>();
  cmd->add_option("--branch-at", *branch_at,
                  "In a window: branch at this time (s) and take over with the mouse (key B "
                  "branches where the replay is)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--branch", *branch_file,
                  "In a window: the branch recording (default: NAME.branch-STEP.lapr beside it)");
  cmd->callback([&action, opts, headless, frames, report, speed, seconds, snapshot, branch_at,
                 branch_file, from, layout_log] {
    action = [opts, headless, frames, report, speed, seconds, snapshot, branch_at, branch_file,
              from, layout_log] {
      if (*from >= 0.0) opts->from_s = *from;
      if (!*headless) {
        if (opts->from_s)
          throw InputError("--from", 0, "starts a headless replay",
                           "--headless (in a window, seek with the keys)");
        const char* x = std::getenv("DISPLAY");
        const char* wl = std::getenv("WAYLAND_DISPLAY");
        if ((x == nullptr || *x == '\0') && (wl == nullptr || *wl == '\0'))
          throw InputError(opts->recording.string(), 0,
                           "replay in a window needs a display and none is set",
                           "DISPLAY or WAYLAND_DISPLAY; without one use --headless");
        ReplayWindowOptions wo;
        wo.speed = *speed;
        wo.seconds = *seconds;
        wo.snapshot = *snapshot;
        wo.layout_log = *layout_log;
        if (*branch_at >= 0.0) wo.branch_at_s = *branch_at;
        if (!branch_file->empty()) wo.branch_file = *branch_file;
        return run_replay_window(opts->recording, wo);
      }
      if (!frames->empty()) opts->frames = *frames;
      if (!report->empty()) opts->report = *report;
      const ReplayResult r = run_replay(*opts);
      std::printf("%s\n", r.report.dump(2).c_str());
      if (!r.damage.empty())
        std::fprintf(stderr, "warning: %s: %s; replayed %llu steps\n",
                     opts->recording.string().c_str(), r.damage.c_str(),
                     static_cast<unsigned long long>(r.steps));
      if (r.diverged_at) {
        std::fprintf(stderr, "error: replay diverged from the recording at step %llu\n",
                     static_cast<unsigned long long>(*r.diverged_at));
        return 3;
      }
      if (r.snapshot_diverged_at) {
        std::fprintf(
            stderr, "error: replay diverged from the recording's snapshot after step %llu (%s)\n",
            static_cast<unsigned long long>(*r.snapshot_diverged_at), r.snapshot_part.c_str());
        return 3;
      }
      if (opts->verify && r.corrupt) {
        std::fprintf(stderr, "error: recording corrupt: %s\n", r.damage.c_str());
        return 4;
      }
      return 0;
    };
  });
}

}  // namespace serosa::replay
