// Trace format version 2: an anti-aliased pixel's section (its samples, adaptive squares and value) and each
// ray's sample, recorded by record_pixel_trace as the renderer samples the pixel; the round trip write ->
// read
// -> write; version 1 documents still read; damaged pixel sections refused with the file, line and JSON path;
// the CSV's sample column.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <random>
#include <string>

#include "loaded_scene.h"
#include "raystep/accel/accelerator.h"
#include "raystep/io/scene_loader.h"
#include "raystep/render/render.h"
#include "raystep/scene/antialiasing_spec.h"
#include "raystep/trace/record_trace.h"
#include "raystep/trace/trace_file.h"
#include "raystep/util/error.h"
#include "test_budget.h"

namespace raystep {
namespace {

// A shipped scene whose pixels are traced into a trace file.
struct TracedScene : test::LoadedScene {
  using test::LoadedScene::LoadedScene;
  Trace trace(const std::string& spec, int x, int y, bool secondary, uint64_t seed = 3) const {
    return record_pixel_trace(scene, *accel, scene.render.width, scene.render.height, x, y,
                              parse_antialiasing(spec), seed, secondary, "scene.json", "fnv1a64:0");
  }
};

bool same_bits(const glm::vec3& a, const glm::vec3& b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

int line_of(const std::string& text, const std::string& needle) {
  size_t at = text.find(needle);
  return 1 + int(std::count(text.begin(), text.begin() + long(at), '\n'));
}

// Replaces the value after the first `key` (up to the next ',' or '}') and expects a refusal that names the
// file, the line of that value and the message part.
void expect_refused(const std::string& text, const std::string& key, const std::string& value,
                    const std::string& message_part) {
  std::string bad = text;
  size_t at = bad.find(key);
  ASSERT_NE(at, std::string::npos) << key;
  size_t begin = at + key.size();
  size_t end = begin;
  int nesting = 0;
  while (end < bad.size() && (nesting > 0 || (bad[end] != ',' && bad[end] != '}'))) {
    if (bad[end] == '[') ++nesting;
    if (bad[end] == ']') --nesting;
    ++end;
  }
  bad.replace(begin, end - begin, value);
  try {
    parse_trace_json(bad, "bad.json");
    ADD_FAILURE() << "accepted " << key << value;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "bad.json");
    EXPECT_EQ(e.line(), line_of(text, key)) << e.what();
    EXPECT_NE(std::string(e.what()).find(message_part), std::string::npos) << e.what();
  }
}

// Pixel (30, 38) of the aliasing scene is crossed by the triangle's lower edge: adaptive sampling subdivides
// it.
constexpr int kEdgeX = 30, kEdgeY = 38;

TEST(PixelTrace, RecordsThePixelAsTheRendererSamplesIt) {
  const TracedScene s("aliasing.json");
  for (const char* spec :
       {"none", "regular:3", "jitter:4", "random:7", "adaptive:0.1:2", "adaptive:0.05:4"}) {
    SCOPED_TRACE(spec);
    const Trace t = s.trace(spec, kEdgeX, kEdgeY, false);
    ASSERT_TRUE(t.pixel);
    const PixelSampling& p = t.pixel->sampling;
    EXPECT_EQ(to_string(p.aa), spec);
    EXPECT_EQ(t.pixel->width, 64);
    EXPECT_EQ(t.pixel->height, 48);
    EXPECT_EQ(t.pixel->seed, 3u);
    EXPECT_FALSE(t.pixel->exact);
    // The renderer's pixel, value and sample count.
    RenderOptions o;
    o.aa = p.aa;
    o.width = 64;
    o.height = 48;
    o.seed = 3;
    const RenderResult r = render_image(s.scene, *s.accel, o);
    const size_t pixel = size_t(kEdgeY) * 64 + kEdgeX;
    EXPECT_TRUE(same_bits(p.value, r.image.pixels[pixel]));
    EXPECT_EQ(p.samples.size(), r.samples[pixel]);
    // One primary ray per sample, in order.
    ASSERT_EQ(t.rays.size(), p.samples.size());
    for (size_t i = 0; i < t.rays.size(); ++i) {
      EXPECT_EQ(t.rays[i].sample, int(i));
      EXPECT_EQ(t.rays[i].kind, RayKind::primary);
      EXPECT_TRUE(t.rays[i].has_pixel);
    }
    if (p.aa.mode == AntiAliasing::Mode::adaptive) EXPECT_GT(p.squares.size(), 1u);
  }
}

TEST(PixelTrace, JsonRoundTripIsIdenticalForEveryPattern) {
  const TracedScene aliasing("aliasing.json");
  const TracedScene spheres("spheres.json", "kd");
  for (const char* spec : {"none", "regular:2", "jitter:3", "random:5", "adaptive:0.1:3"}) {
    SCOPED_TRACE(spec);
    for (Trace t : {aliasing.trace(spec, kEdgeX, kEdgeY, false), spheres.trace(spec, 170, 120, true)}) {
      t.pixel->exact = glm::vec3(0.25f, 1.f / 3.f, 0.f);
      const std::string once = trace_to_json(t);
      const Trace back = parse_trace_json(once, "mem.json");
      EXPECT_EQ(trace_to_json(back), once);
      EXPECT_EQ(back.version, kTraceVersion);
      ASSERT_TRUE(back.pixel);
      const PixelSampling &a = t.pixel->sampling, &b = back.pixel->sampling;
      ASSERT_EQ(a.samples.size(), b.samples.size());
      for (size_t i = 0; i < a.samples.size(); ++i) {
        EXPECT_EQ(std::memcmp(&a.samples[i].px, &b.samples[i].px, sizeof(float)), 0);
        EXPECT_EQ(std::memcmp(&a.samples[i].py, &b.samples[i].py, sizeof(float)), 0);
        EXPECT_TRUE(same_bits(a.samples[i].colour, b.samples[i].colour));
        EXPECT_EQ(a.samples[i].stratum[0], b.samples[i].stratum[0]);
        EXPECT_EQ(a.samples[i].lattice[1], b.samples[i].lattice[1]);
      }
      ASSERT_EQ(a.squares.size(), b.squares.size());
      for (size_t i = 0; i < a.squares.size(); ++i) {
        EXPECT_EQ(a.squares[i].parent, b.squares[i].parent);
        EXPECT_EQ(a.squares[i].outcome, b.squares[i].outcome);
        EXPECT_EQ(std::memcmp(a.squares[i].children, b.squares[i].children, sizeof a.squares[i].children), 0);
        EXPECT_EQ(std::memcmp(a.squares[i].samples, b.squares[i].samples, sizeof a.squares[i].samples), 0);
        EXPECT_EQ(a.squares[i].new_samples, b.squares[i].new_samples);
        EXPECT_TRUE(same_bits(a.squares[i].contrast, b.squares[i].contrast));
        EXPECT_TRUE(same_bits(a.squares[i].value, b.squares[i].value));
      }
      EXPECT_TRUE(same_bits(a.value, b.value));
      ASSERT_TRUE(back.pixel->exact);
      EXPECT_TRUE(same_bits(*back.pixel->exact, *t.pixel->exact));
      ASSERT_EQ(back.rays.size(), t.rays.size());
      for (size_t i = 0; i < t.rays.size(); ++i) EXPECT_EQ(back.rays[i].sample, t.rays[i].sample);
      // The summary states the pattern, the samples and the value.
      const std::string summary = trace_summary(back);
      EXPECT_NE(summary.find("aa " + std::string(spec)), std::string::npos) << summary;
      EXPECT_NE(summary.find(std::to_string(b.samples.size()) + " sample(s)"), std::string::npos) << summary;
    }
  }
  // Secondary rays carry the sample of the primary ray they descend from.
  const Trace t = spheres.trace("jitter:2", 170, 120, true);
  int secondary = 0;
  for (size_t i = 0; i < t.rays.size(); ++i) {
    if (t.rays[i].kind == RayKind::primary) continue;
    ++secondary;
    EXPECT_GT(i, 0u);
    EXPECT_EQ(t.rays[i].sample, t.rays[i - 1].sample);
  }
  EXPECT_GT(secondary, 0);
}

// A version 1 document, as the version 1 writer wrote it (docs/trace-format.md's example).
const char* const kVersion1 = R"({
 "format": "raystep-trace",
 "version": 1,
 "scene": {"path":"a","hash":"b","primitives":2},
 "structure": {"kind":"grid","bounds_min":[0.0,-1.0,0.0],"bounds_max":[3.0,2.0,1.0],"resolution":[3,1,1],"density":3,"insert":"exact","references":4},
 "rays": [
  {"origin":[-1.0,0.5,0.5],"direction":[1.0,0.0,0.0],"tmin":0.0,"tmax":"inf","kind":"primary","depth":0,"pixel":[12,7],"counters":{"cells":2,"nodes":0,"prim_tests":2,"prim_hits":2,"mailbox_hits":1,"pushes":0,"pops":0},
   "events": [
    {"seq":0,"type":"ray_begin"},
    {"seq":1,"type":"cell","cell":[0,0,0],"t_enter":1.0,"t_exit":2.0,"t_max":[2.0,"inf","inf"],"t_delta":[1.0,"inf","inf"],"next_axis":"x"},
    {"seq":2,"type":"prim_test","prim":0,"hit":true,"t":3.5},
    {"seq":3,"type":"hit_deferred","prim":0,"t":3.5,"t_exit":2.0},
    {"seq":4,"type":"cell","cell":[1,0,0],"t_enter":2.0,"t_exit":3.0,"t_max":[3.0,"inf","inf"],"t_delta":[1.0,"inf","inf"],"next_axis":"x"},
    {"seq":5,"type":"mailbox_hit","prim":0},
    {"seq":6,"type":"prim_test","prim":1,"hit":true,"t":2.5},
    {"seq":7,"type":"hit_accepted","prim":1,"t":2.5,"reason":"inside_cell"},
    {"seq":8,"type":"ray_end","prim":1,"t":2.5}
   ]}
 ],
 "geometry": {
  "cells": [
   {"cell":[0,0,0],"min":[0.0,-1.0,0.0],"max":[1.0,2.0,1.0]},
   {"cell":[1,0,0],"min":[1.0,-1.0,0.0],"max":[2.0,2.0,1.0]}
  ],
  "primitives": [
   {"id":0,"type":"triangle","vertices":[[0.0,-1.0,0.0],[0.0,2.0,0.0],[3.0,0.5,0.6000000238418579]]},
   {"id":1,"type":"triangle","vertices":[[1.5,0.0,0.0],[1.5,1.0,0.0],[1.5,0.0,1.0]]}
  ]
 }
}
)";

TEST(PixelTrace, Version1DocumentsStillRead) {
  const Trace t = parse_trace_json(kVersion1, "v1.json");
  EXPECT_EQ(t.version, 1);
  EXPECT_FALSE(t.pixel);
  ASSERT_EQ(t.rays.size(), 1u);
  EXPECT_EQ(t.rays[0].sample, -1);
  EXPECT_EQ(t.rays[0].pixel[0], 12);
  EXPECT_EQ(t.rays[0].events.size(), 9u);
  // Written back it is a version 4 document that differs in the version and the box_tests counter only.
  std::string v3 = kVersion1;
  v3.replace(v3.find("\"version\": 1"), 12, "\"version\": 4");
  v3.replace(v3.find("\"pops\":0}"), 9, "\"pops\":0,\"box_tests\":0}");
  EXPECT_EQ(trace_to_json(t), v3);
  // The same document as version 2 reads the same.
  std::string v2 = kVersion1;
  v2.replace(v2.find("\"version\": 1"), 12, "\"version\": 2");
  const Trace t2 = parse_trace_json(v2, "v2.json");
  EXPECT_EQ(t2.version, 2);
  EXPECT_EQ(trace_to_json(t2), v3);
  // Version 1 knew no "pixel" nor "sample": a reader ignores keys it does not know, whatever they hold.
  std::string extra = kVersion1;
  extra.replace(extra.find(" \"rays\""), 0, " \"pixel\": {\"x\": \"nonsense\"},\n");
  extra.replace(extra.find("\"pixel\":[12,7]"), 0, "\"sample\":99,");
  const Trace u = parse_trace_json(extra, "v1.json");
  EXPECT_FALSE(u.pixel);
  EXPECT_EQ(u.rays[0].sample, -1);
}

TEST(PixelTrace, DamagedPixelSectionsAreRefusedWithLineAndPath) {
  const TracedScene s("aliasing.json");
  const std::string adaptive = trace_to_json(s.trace("adaptive:0.1:2", kEdgeX, kEdgeY, false));
  const std::string jitter = trace_to_json(s.trace("jitter:2", kEdgeX, kEdgeY, false));
  ASSERT_NE(adaptive.find("\"outcome\":\"subdivided\""), std::string::npos);

  // The pixel's head.
  expect_refused(adaptive, "\"x\":", "64", "pixel.x: value 64 out of range 0..63");
  expect_refused(adaptive, "\"y\":", "-1", "pixel.y: value -1 out of range 0..47");
  expect_refused(adaptive, "\"width\":", "0", "pixel.width: value 0 out of range");
  expect_refused(adaptive, "\"seed\":", "-3", "pixel.seed: expected an integer in 0..2^64-1");
  expect_refused(adaptive, "\"seed\":", "1.5", "pixel.seed: expected an integer");
  expect_refused(adaptive, "\"aa\":", "\"adaptive:7\"", "pixel.aa: bad anti-aliasing 'adaptive:7'");
  expect_refused(adaptive, "\"aa\":", "3", "pixel.aa: expected a string");
  expect_refused(adaptive, "\"value\":", "[1,null,0]",
                 "pixel.value[1]: expected a number, found null (NaN?)");
  expect_refused(adaptive, "\"value\":", "[1,0]", "pixel.value: expected an array of 3 numbers");
  // Samples.
  expect_refused(jitter, "\"samples\":", "[]", "pixel.samples: 0 samples, but jitter:2 casts 4");
  expect_refused(adaptive, "\"samples\":", "[]", "pixel.samples: 0 samples, but adaptive:0.1:2 casts 5..");
  expect_refused(adaptive, "\"px\":", "31.5", "pixel.samples[0].px: outside pixel 30's span");
  expect_refused(adaptive, "\"py\":", "null", "pixel.samples[0].py: expected a number, found null");
  expect_refused(adaptive, "\"colour\":", "[0,0,1e39]",
                 "pixel.samples[0].colour[2]: number out of float range");
  expect_refused(adaptive, "\"lattice\":", "[0,9]", "pixel.samples[0].lattice[1]: value 9 out of range 0..8");
  expect_refused(adaptive, "\"lattice\":", "[0]", "pixel.samples[0].lattice: expected [i, j]");
  expect_refused(jitter, "\"stratum\":", "[2,0]", "pixel.samples[0].stratum[0]: value 2 out of range 0..1");
  expect_refused(jitter, "\"colour\":", "[0,0,0],\"lattice\":[0,0]",
                 "pixel.samples[0].lattice: only adaptive samples lie on the lattice");
  // The adaptive squares.
  expect_refused(adaptive, "\"squares\":", "[]", "pixel.squares: adaptive sampling has at least");
  expect_refused(jitter, "\"squares\":", "[{}]", "pixel.squares: only adaptive sampling has squares");
  expect_refused(adaptive, "\"parent\":", "0", "pixel.squares[0].parent: value 0 out of range -1..-1");
  expect_refused(adaptive, "\"depth\":0,\"i0\":", "9", "pixel.squares[0].i0: value 9 out of range 0..8");
  expect_refused(adaptive, "\"new_samples\":", "6",
                 "pixel.squares[0].new_samples: value 6 out of range 0..5");
  expect_refused(adaptive, "\"outcome\":", "\"maybe\"",
                 "pixel.squares[0].outcome: unknown outcome \"maybe\"");
  expect_refused(adaptive, "\"children\":", "[1,2,3]", "pixel.squares[0].children: expected 4 children");
  expect_refused(adaptive, "\"children\":", "[0,2,3,4]",
                 "pixel.squares[0].children[0]: value 0 out of range");
  expect_refused(adaptive, "\"contrast\":", "[0.5,\"nan\",0]",
                 "pixel.squares[0].contrast[1]: expected a number");
  expect_refused(adaptive, "\"size\":8,\"samples\":", "[0,1,2,3,999]",
                 "pixel.squares[0].samples[4]: value 999 out of range");
  // A child that names another parent, and a leaf that lists children.
  {
    std::string bad = adaptive;
    const std::string second = "\"parent\":0,";
    const size_t at = bad.find(second);
    ASSERT_NE(at, std::string::npos);
    bad.replace(at, second.size(), "\"parent\":-1,");
    EXPECT_THROW(parse_trace_json(bad, "bad.json"), InputError);
    expect_refused(adaptive, "\"outcome\":\"agree\",\"children\":", "[0,-1,-1,-1]",
                   "children[0]: value 0 out of range -1..-1");
  }
  // A ray's sample.
  expect_refused(adaptive, "\"sample\":", "99", "rays[0].sample: value 99 out of range");
  std::string no_pixel = adaptive;
  const size_t from = no_pixel.find(" \"pixel\": {"), to = no_pixel.find(" \"rays\":");
  no_pixel.erase(from, to - from);
  expect_refused(no_pixel, "\"sample\":", "0",
                 "rays[0].sample: a ray's sample needs the trace's \"pixel\" section");
}

// Random damage to a pixel trace's pixel section: the reader reads something that reads back the same, or
// refuses it with the file named; never another exception.
TEST(PixelTrace, DamagedPixelSectionsNeverCrashTheReader) {
  const TracedScene s("aliasing.json");
  const std::string text = trace_to_json(s.trace("adaptive:0.1:2", kEdgeX, kEdgeY, false));
  const size_t begin = text.find(" \"pixel\""), end = text.find(" \"rays\"");
  const char* values[] = {"0",
                          "1",
                          "-1",
                          "5",
                          "8",
                          "9",
                          "64",
                          "1e400",
                          "0.5",
                          "null",
                          "[]",
                          "{}",
                          "[0,0]",
                          "true",
                          "\"\"",
                          "\"agree\"",
                          "\"subdivided\"",
                          "\"depth_limit\"",
                          "[1,2,3,4]",
                          "[-1,-1,-1,-1]",
                          "\"none\"",
                          "\"jitter:2\""};
  std::mt19937 rng(7);
  int accepted = 0, refused = 0;
  for (int trial = 0; trial < test::budget(1500); ++trial) {
    std::string bad = text;
    // Replace one token (a number, string or literal) inside the pixel section.
    size_t at = begin + rng() % (end - begin);
    while (at < end &&
           !(std::isalnum(static_cast<unsigned char>(bad[at])) || bad[at] == '-' || bad[at] == '"'))
      ++at;
    if (at >= end) continue;
    size_t stop = at + 1;
    if (bad[at] == '"') {
      while (stop < end && bad[stop] != '"') ++stop;
      ++stop;
      if (bad[stop] == ':') continue;  // a key: left alone
    } else {
      while (stop < end && (std::isalnum(static_cast<unsigned char>(bad[stop])) || bad[stop] == '.' ||
                            bad[stop] == '-' || bad[stop] == '+'))
        ++stop;
    }
    bad.replace(at, stop - at, values[rng() % std::size(values)]);
    try {
      const std::string got = trace_to_json(parse_trace_json(bad, "x.json"));
      EXPECT_EQ(trace_to_json(parse_trace_json(got, "x.json")), got);
      ++accepted;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), "x.json");
      ++refused;
    }
  }
  EXPECT_GT(refused, 0);
  EXPECT_GT(accepted, 0);
}

TEST(PixelTrace, CsvAppendsTheSampleColumn) {
  const TracedScene s("aliasing.json");
  const Trace t = s.trace("regular:2", kEdgeX, kEdgeY, false);
  const std::string path = ::testing::TempDir() + "/pixel_trace.csv";
  write_trace_csv(path, t);
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  // The version 1 columns first, unchanged; the sample after them; version 3's parent (box_test) last.
  EXPECT_EQ(
      line,
      "ray,seq,type,i,j,k,t_enter,t_exit,t_max_x,t_max_y,t_max_z,t_delta_x,t_delta_y,t_delta_z,next_axis,"
      "node,depth,t_min,t_max,prim,hit,t,reason,sample,parent");
  size_t rows = 0;
  while (std::getline(in, line)) {
    const size_t ray = size_t(std::stoi(line.substr(0, line.find(','))));
    const std::string head = line.substr(0, line.rfind(','));  // a grid trace's parent column is empty
    EXPECT_EQ(line.substr(head.size()), ",") << line;
    EXPECT_EQ(head.substr(head.rfind(',') + 1), std::to_string(t.rays[ray].sample)) << line;
    ++rows;
  }
  size_t events = 0;
  for (const TracedRay& r : t.rays) events += r.events.size();
  EXPECT_EQ(rows, events);
}

TEST(PixelTrace, BadRequestsThrow) {
  const TracedScene s("aliasing.json");
  EXPECT_THROW(s.trace("jitter:2", 64, 0, false), InputError);
  EXPECT_THROW(s.trace("jitter:2", 0, -1, false), InputError);
  AntiAliasing zero = parse_antialiasing("adaptive:0.1:2");
  zero.threshold = 0.f;  // valid for the sampler, but no spec says it
  EXPECT_THROW(record_pixel_trace(s.scene, *s.accel, 64, 48, 1, 1, zero, 0, false, "a", "b"), InputError);
  auto brute = make_accelerator("brute");
  brute->build(s.scene.geometry);
  EXPECT_THROW(
      record_pixel_trace(s.scene, *brute, 64, 48, 1, 1, parse_antialiasing("none"), 0, false, "a", "b"),
      InputError);
}

}  // namespace
}  // namespace raystep
