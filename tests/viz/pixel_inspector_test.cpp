// The pixel inspector (suite PixelInspector), run as a user would drive raystep-gui in scripted mode: the
// samples it shows are the sampler's and the renderer's (every mode), its adaptive squares and their outcomes
// are core's in the order they were visited, a sample picked on the canvas replays the very ray the renderer
// cast for it, the error heat map is offered only where an exact reference exists, and a trace of an
// anti-aliased pixel opens with its inspector. Run under Xvfb (CTest does).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "raystep/accel/structure_options.h"
#include "raystep/render/camera.h"
#include "raystep/render/pixel_samples.h"
#include "raystep/render/reference.h"
#include "raystep/render/render.h"
#include "raystep/render/whitted.h"
#include "raystep/scene/antialiasing_spec.h"
#include "raystep/io/scene_loader.h"
#include "viz_test_util.h"

namespace {

using namespace raystep;
using namespace raystep::viztest;

const std::string kAliasing = kSourceDir + "/scenes/aliasing.json";
const std::string kCornell = kSourceDir + "/scenes/cornell.json";
// Pixel (30, 38) of the aliasing scene straddles the triangle's lower edge (from (6, 5) to (58, 14)).
const int kX = 30, kY = 38;

// Core's recording of a pixel, with the renderer's random stream and radiance.
struct CoreSide {
  Scene scene;
  std::unique_ptr<Accelerator> accel;
  explicit CoreSide(const std::string& path) : scene(load_scene(path)) {
    accel = make_accelerator("grid", StructureOptions{});
    accel->build(scene.geometry);
  }
  PixelSampling sample(const std::string& aaSpec, int x, int y) const {
    const int w = scene.render.width, h = scene.render.height;
    Pcg32 rng = pixel_rng(scene.render.seed, x, y, w);
    const ProjectiveCamera camera(scene.camera, w, h);
    const WhittedTracer tracer(scene, *accel);
    RayCounts counts;
    return sample_pixel(parse_antialiasing(aaSpec), x, y, rng, [&](float px, float py) {
      return tracer.trace_primary(camera.generate(px, py), &counts);
    });
  }
  glm::vec3 rendered(const std::string& aaSpec, int x, int y) const {
    RenderOptions o = render_options(scene.render);
    o.aa = parse_antialiasing(aaSpec);
    return render_image(scene, *accel, o).image.at(x, y);
  }
};

json inspect(const std::string& args, const std::string& tag) {
  const std::string dump = kOut + "/" + tag + ".json";
  GuiRun r = gui(args + " --window 1280x800 --dump-state '" + dump + "' --quit", tag);
  EXPECT_EQ(r.code, 0) << args << "\n" << r.err;
  return r.code == 0 ? readJson(dump) : json::object();
}

const char* outcomeName(AdaptiveSquare::Outcome o) {
  switch (o) {
    case AdaptiveSquare::Outcome::agree:
      return "agree";
    case AdaptiveSquare::Outcome::depth_limit:
      return "depth limit";
    case AdaptiveSquare::Outcome::subdivided:
      return "split";
  }
  return "?";
}

TEST(PixelInspector, PositionsAndColoursAreTheSamplersAndTheRenderers) {
  const CoreSide core(kAliasing);
  for (const std::string aa : {"none", "regular:3", "jitter:4", "random:5", "adaptive:0.1:3"}) {
    SCOPED_TRACE(aa);
    const json st = inspect("'" + kAliasing + "' --aa " + aa + " --pixel 30,38 --inspect",
                            "pixel-inspector-" + aa.substr(0, aa.find(':')));
    const json& in = st["inspector"];
    ASSERT_TRUE(in.value("visible", false));
    const PixelSampling want = core.sample(aa, kX, kY);
    ASSERT_EQ(in["samples"].size(), want.samples.size());
    ASSERT_GT(want.samples.size(), 0u);
    for (size_t i = 0; i < want.samples.size(); ++i) {
      const json& s = in["samples"][i];
      EXPECT_EQ(s[0].get<float>(), want.samples[i].px) << i;
      EXPECT_EQ(s[1].get<float>(), want.samples[i].py) << i;
      for (int c = 0; c < 3; ++c) EXPECT_EQ(s[2 + c].get<float>(), want.samples[i].colour[c]) << i;
      // Inside the pixel; jittered samples inside their own stratum.
      EXPECT_GE(want.samples[i].px, float(kX));
      EXPECT_LE(want.samples[i].px, float(kX + 1));
      if (aa.rfind("jitter", 0) == 0) {
        EXPECT_GE(want.samples[i].px, float(kX) + want.samples[i].stratum[0] / 4.f);
        EXPECT_LE(want.samples[i].px, float(kX) + (want.samples[i].stratum[0] + 1) / 4.f);
      }
    }
    // The average is the renderer's pixel, bit for bit.
    const glm::vec3 rendered = core.rendered(aa, kX, kY);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(in["value"][size_t(c)].get<float>(), rendered[c]);
    // The scene is flat and orthographic: the exact value is shown with the error of the average.
    ASSERT_TRUE(in.contains("exact"));
    EXPECT_NE(in["values"].get<std::string>().find("error of the "), std::string::npos);
    // The scene inside the pixel beneath the samples, and the legend says so.
    EXPECT_TRUE(in["backdrop"].get<bool>());
    EXPECT_NE(in["legend"].get<std::string>().find("scene inside the pixel"), std::string::npos);
    // Every sample's ray is in the trace (without anti-aliasing: the centre ray).
    EXPECT_EQ(st["trace_rays"].get<size_t>(), want.samples.size());
  }
}

// Sampling and pre-filtering combined: the tent pixel's own samples, its neighbours' that the tent reaches,
// the weighted value (the renderer's) and the exact tent value (core's), and a canvas that shows the tent's
// square with the neighbours' samples inside it.
TEST(PixelInspector, TentFilterWeighsTheNeighboursSamplesAsTheRendererDoes) {
  const CoreSide core(kAliasing);
  const std::string aa = "jitter:3+tent";
  const json st = inspect("'" + kAliasing + "' --aa " + aa + " --pixel 30,38 --inspect", "pixel-inspector-tent");
  const json& in = st["inspector"];
  ASSERT_TRUE(in.value("visible", false));
  EXPECT_EQ(in["filter"], "tent");
  PixelSampling want = core.sample(aa, kX, kY);
  const glm::vec3 box = want.value;
  {
    const int w = core.scene.render.width, h = core.scene.render.height;
    const ProjectiveCamera camera(core.scene.camera, w, h);
    const WhittedTracer tracer(core.scene, *core.accel);
    RayCounts counts;
    apply_pixel_filter(want, core.scene.render.seed, w,
                       [&](float px, float py) { return tracer.trace_primary(camera.generate(px, py), &counts); });
  }
  EXPECT_EQ(in["samples"].size(), 9u);
  EXPECT_EQ(in["neighbours"].get<size_t>(), want.neighbours.size());
  EXPECT_GT(want.neighbours.size(), 0u);
  const glm::vec3 rendered = core.rendered(aa, kX, kY);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(in["value"][size_t(c)].get<float>(), rendered[c]);
    EXPECT_EQ(in["box_value"][size_t(c)].get<float>(), box[c]);
  }
  // The edge crosses the pixel: the tent's value is not the box's.
  EXPECT_NE(rendered, box);
  ASSERT_TRUE(in.contains("exact"));
  const std::optional<glm::vec3> exact =
      exact_pixel_value(core.scene, core.scene.render.width, core.scene.render.height, kX, kY,
                        AntiAliasing::Filter::tent);
  ASSERT_TRUE(exact);
  EXPECT_EQ(in["exact"][0].get<float>(), exact->x);
  EXPECT_NE(in["values"].get<std::string>().find("the tent over the area covered"), std::string::npos);
  EXPECT_NE(in["legend"].get<std::string>().find("scene under the tent"), std::string::npos);
  // Only the pixel's own samples have rays in the trace.
  EXPECT_EQ(st["trace_rays"].get<size_t>(), 9u);
}

TEST(PixelInspector, AdaptiveSteppingVisitsTheSquaresInOrderWithCoresOutcomes) {
  const CoreSide core(kAliasing);
  const PixelSampling want = core.sample("adaptive:0.1:3", kX, kY);
  ASSERT_GT(want.squares.size(), 5u) << "the edge pixel should be subdivided";
  // Ctrl+Right steps one square at a time, depth first; Ctrl+End goes to the last; --square jumps.
  const std::string base = "'" + kAliasing + "' --aa adaptive:0.1:3 --pixel 30,38 --inspect";
  const json a = inspect(base + " --keys Ctrl+Right,Ctrl+Right,Ctrl+Right", "pixel-inspector-steps");
  const json& in = a["inspector"];
  ASSERT_EQ(in["squares"].size(), want.squares.size());
  for (size_t i = 0; i < want.squares.size(); ++i) {
    const json& q = in["squares"][i];
    EXPECT_EQ(q["depth"].get<int>(), want.squares[i].depth) << i;
    EXPECT_EQ(q["i0"].get<int>(), want.squares[i].i0) << i;
    EXPECT_EQ(q["j0"].get<int>(), want.squares[i].j0) << i;
    EXPECT_EQ(q["size"].get<int>(), want.squares[i].size) << i;
    EXPECT_EQ(q["outcome"].get<std::string>(), outcomeName(want.squares[i].outcome)) << i;
  }
  EXPECT_EQ(in["square"].get<int>(), 3);
  EXPECT_EQ(in["tree_current"].get<int>(), 3);
  // The Why of each square says what core decided, with its numbers.
  for (int k : {0, int(want.squares.size()) - 1}) {
    const json b = inspect(base + " --square " + std::to_string(k), "pixel-inspector-square");
    const std::string why = b["inspector"]["why"].get<std::string>();
    switch (want.squares[size_t(k)].outcome) {
      case AdaptiveSquare::Outcome::subdivided:
        EXPECT_NE(why.find("split into four"), std::string::npos) << why;
        break;
      case AdaptiveSquare::Outcome::agree:
        EXPECT_NE(why.find("samples agree"), std::string::npos) << why;
        break;
      case AdaptiveSquare::Outcome::depth_limit:
        EXPECT_NE(why.find("depth limit 3"), std::string::npos) << why;
        break;
    }
    EXPECT_NE(why.find("threshold 0.1"), std::string::npos) << why;
  }
  EXPECT_EQ(want.squares[0].outcome, AdaptiveSquare::Outcome::subdivided);
  const json last = inspect(base + " --keys Ctrl+End", "pixel-inspector-end");
  EXPECT_EQ(last["inspector"]["square"].get<int>(), int(want.squares.size()) - 1);
  // Out of range, or not adaptive: one line, exit 2.
  GuiRun bad = gui(base + " --square 999 --quit", "pixel-inspector-bad-square");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("error: --square 999"), std::string::npos) << bad.err;
  GuiRun bad2 =
      gui("'" + kAliasing + "' --aa jitter:2 --pixel 30,38 --sample 4 --quit", "pixel-inspector-bad-sample");
  EXPECT_EQ(bad2.code, 2);
  EXPECT_NE(bad2.err.find("the pixel has 4 samples"), std::string::npos) << bad2.err;
}

TEST(PixelInspector, PickedSampleReplaysTheRenderersRay) {
  const CoreSide core(kCornell);
  const PixelSampling want = core.sample("jitter:2", 160, 200);
  ASSERT_EQ(want.samples.size(), 4u);
  const json st = inspect("'" + kCornell + "' --aa jitter:2 --pixel 160,200 --secondary --click-sample 2",
                          "pixel-inspector-pick");
  EXPECT_EQ(st["inspector"]["sample"].get<int>(), 2);
  EXPECT_EQ(st["inspector"]["table_row"].get<int>(), 2);
  EXPECT_EQ(st["ray_sample"].get<int>(), 2);
  EXPECT_EQ(st["ray_kind"].get<std::string>(), "primary");
  EXPECT_EQ(st["step"].get<int>(), 0);
  // The ray the renderer cast for that sample.
  const Ray ray =
      ProjectiveCamera(core.scene.camera, 320, 320).generate(want.samples[2].px, want.samples[2].py);
  for (int c = 0; c < 3; ++c) {
    EXPECT_FLOAT_EQ(st["ray_origin"][size_t(c)].get<float>(), ray.origin[c]);
    EXPECT_FLOAT_EQ(st["ray_dir"][size_t(c)].get<float>(), ray.direction[c]);
  }
  // With secondary rays on, the trace holds more than the four primary rays.
  EXPECT_GT(st["trace_rays"].get<int>(), 4);
}

TEST(PixelInspector, ErrorHeatMapIsOfferedOnlyWithAReference) {
  const json flat = inspect("'" + kAliasing + "' --aa none --heat error", "pixel-inspector-error-heat");
  EXPECT_TRUE(flat["heat"]["error_available"].get<bool>());
  EXPECT_EQ(flat["heat"]["quantity"].get<std::string>(), "error");
  EXPECT_GT(flat["heat"]["max"].get<double>(), 0.0);  // the unfiltered edges are wrong
  const json lit = inspect("'" + kCornell + "'", "pixel-inspector-no-error-heat");
  EXPECT_FALSE(lit["heat"]["error_available"].get<bool>());
  EXPECT_FALSE(lit["heat"]["error_why_not"].get<std::string>().empty());
  // In the menu: greyed out, and its tooltip says why.
  EXPECT_TRUE(flat["heat"]["error_item_enabled"].get<bool>());
  EXPECT_FALSE(lit["heat"]["error_item_enabled"].get<bool>());
  EXPECT_NE(lit["heat"]["error_item_tooltip"].get<std::string>().find(
                lit["heat"]["error_why_not"].get<std::string>()),
            std::string::npos);
}

TEST(PixelInspector, TraceOfAnAntiAliasedPixelOpensWithItsInspector) {
  const std::string trace = kOut + "/pixel-inspector-trace.json";
  const json scene = inspect("'" + kAliasing + "' --aa jitter:3 --pixel 30,38 --export-trace '" + trace + "'",
                             "pixel-inspector-export");
  EXPECT_FALSE(scene["inspector"]["visible"].get<bool>());  // not asked for in scripted mode
  const json opened = inspect("'" + trace + "' --sample 4", "pixel-inspector-open-trace");
  ASSERT_TRUE(opened.contains("inspector"));
  const json& in = opened["inspector"];
  EXPECT_TRUE(in["visible"].get<bool>());
  EXPECT_EQ(in["samples"], scene["inspector"]["samples"]);
  EXPECT_EQ(in["value"], scene["inspector"]["value"]);
  EXPECT_EQ(in["exact"], scene["inspector"]["exact"]);
  EXPECT_EQ(in["sample"].get<int>(), 4);
  EXPECT_FALSE(in["backdrop"].get<bool>());  // no scene to look inside the pixel
  EXPECT_EQ(opened["ray_sample"].get<int>(), 4);
}

#ifdef RAYSTEP_CLI_EXE
// The GUI's trace of an anti-aliased pixel is the command line's, byte for byte (Cornell: no exact value).
TEST(PixelInspector, ExportedPixelTraceIsTheCommandLinesTrace) {
  const std::string gt = kOut + "/pixel-export-gui.json", ct = kOut + "/pixel-export-cli.json";
  GuiRun r =
      gui("'" + kCornell + "' --aa jitter:2 --pixel 160,200 --secondary --export-trace '" + gt + "' --quit",
          "pixel-export");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string cmd = "'" + std::string(RAYSTEP_CLI_EXE) + "' trace '" + kCornell +
                          "' --pixel 160,200 --aa jitter:2 --secondary -o '" + ct + "' > /dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  EXPECT_EQ(slurp(gt), slurp(ct)) << "the GUI's export and `raystep trace --aa` differ";
}
#endif

TEST(PixelInspector, OverlayDrawsOnlyTheVisiblePixels) {
  const json st = inspect("'" + kAliasing + "' --aa jitter:4 --pixel 30,38 --zoom 12 --sample-overlay",
                          "pixel-inspector-overlay");
  const int drawn = st["sample_overlay"]["pixels_drawn"].get<int>();
  EXPECT_GT(drawn, 20);
  EXPECT_LT(drawn, 64 * 48);
  const json off = inspect("'" + kAliasing + "' --aa jitter:4 --pixel 30,38 --zoom 4 --sample-overlay",
                           "pixel-inspector-overlay-small");
  EXPECT_EQ(off["sample_overlay"]["pixels_drawn"].get<int>(), 0);  // below 8x there is no room for it
}

}  // namespace
