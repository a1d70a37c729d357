// The render side of the solver -> render hand-off: a producer thread publishes frames through
// engine's TripleBuffer as fast as it can while this thread draws the newest one. The producer
// never waits (it finishes all its publishes however slow drawing is), every frame drawn is one
// whole published frame (never a mix of two), and indices are uploaded only when the topology
// version changes.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <thread>

#include "engine/triple_buffer.h"
#include "render/frame_renderer.h"
#include "render/gl_context.h"
#include "render/render_fixtures.h"

namespace serosa::render {
namespace {

TEST(RenderThread, DrawsWholeFramesWhileTheProducerNeverWaits) {
  std::unique_ptr<OffscreenContext> ctx;
  try {
    ctx = std::make_unique<OffscreenContext>(96, 72, 1);
    fixtures::pin_gl_driver();
  } catch (const std::exception& e) {
    FAIL() << e.what();
  }
  const auto sphere = fixtures::icosphere(1, 0.02f);
  TripleBuffer<RenderFrame> frames;
  constexpr int kFrames = 3000;
  constexpr int kPerTopology = 1000;  // the topology changes every 1000 frames (a "cut")
  FrameRenderer renderer;
  SnapshotOptions o;
  o.width = 96;
  o.height = 72;
  std::atomic<bool> done{false};
  std::thread producer([&] {
    for (int k = 1; k <= kFrames; ++k) {
      RenderFrame& f = frames.back();
      if (f.tri.empty()) f = fixtures::frame_of(sphere);
      // Frame k: every position shifted by k micrometres along x, tagged k in the overlay.
      for (std::size_t i = 0; i < f.pos.size(); ++i)
        f.pos[i] = sphere.pos[i] + (i % 3 == 0 ? 1e-6f * static_cast<float>(k) : 0.0f);
      f.overlay.sim_time_s = k;
      f.topology_version = static_cast<std::uint64_t>((k - 1) / kPerTopology);
      // A topology change halves the drawn triangles (as a cut changes them).
      const std::size_t t = sphere.tri.size() / 3 >> f.topology_version;
      f.tri.assign(sphere.tri.begin(), sphere.tri.begin() + static_cast<std::ptrdiff_t>(3 * t));
      f.tri_group.assign(t, 1);
      f.tri_cut.assign(t, 0);
      frames.publish();
      // A solver's pace (~0.1 ms a step here), never waiting for the drawing side.
      std::this_thread::sleep_for(std::chrono::microseconds(100));
    }
    done.store(true);
  });

  int drawn = 0;
  int last_k = 0;
  std::uint64_t versions_seen = 0;
  std::uint64_t last_version = ~0ull;
  for (;;) {
    const bool finished = done.load();  // read before take(): then no publish can be missed
    if (!frames.take()) {
      if (finished) break;
      std::this_thread::yield();
      continue;
    }
    const RenderFrame& f = frames.front();
    const auto k = static_cast<int>(f.overlay.sim_time_s);
    // Whole frames: positions, topology and tag all from the same publish.
    ASSERT_GE(k, last_k);
    for (std::size_t i = 0; i < f.pos.size(); i += 3)
      ASSERT_FLOAT_EQ(f.pos[i], sphere.pos[i] + 1e-6f * static_cast<float>(k));
    ASSERT_EQ(f.topology_version, static_cast<std::uint64_t>((k - 1) / kPerTopology));
    ASSERT_EQ(f.num_triangles(), sphere.tri.size() / 3 >> f.topology_version);
    if (f.topology_version != last_version) {
      ++versions_seen;
      last_version = f.topology_version;
    }
    ctx->bind_framebuffer();
    renderer.draw(f, o, o.width, o.height);
    ++drawn;
    last_k = k;
  }
  producer.join();
  RecordProperty("frames_drawn", drawn);
  EXPECT_GT(drawn, 10);
  EXPECT_EQ(last_k, kFrames);  // the newest frame was drawn in the end
  // Indices went up once per topology version drawn, not once per frame.
  EXPECT_EQ(renderer.topology_uploads(), versions_seen);
  EXPECT_LE(versions_seen, 3u);
}

}  // namespace
}  // namespace serosa::render
