// Anti-aliasing specs (scene/antialiasing_spec.h): each mode's fields, the round trip through to_string,
// and every malformed spec rejected with the expected message.
#include <gtest/gtest.h>

#include "raystep/scene/antialiasing_spec.h"
#include "raystep/util/error.h"

namespace raystep {
namespace {

using Mode = AntiAliasing::Mode;

TEST(AntiAliasingSpec, ReadsEveryMode) {
  AntiAliasing a = parse_antialiasing("none");
  EXPECT_EQ(a.mode, Mode::none);
  EXPECT_EQ(a.k, 1);

  a = parse_antialiasing("regular:4");
  EXPECT_EQ(a.mode, Mode::regular);
  EXPECT_EQ(a.k, 4);

  a = parse_antialiasing("jitter:64");
  EXPECT_EQ(a.mode, Mode::jitter);
  EXPECT_EQ(a.k, 64);

  // random:N keeps the sample count itself in k (not its square root).
  a = parse_antialiasing("random:4096");
  EXPECT_EQ(a.mode, Mode::random);
  EXPECT_EQ(a.k, 4096);

  a = parse_antialiasing("adaptive:0.05");
  EXPECT_EQ(a.mode, Mode::adaptive);
  EXPECT_FLOAT_EQ(a.threshold, 0.05f);
  EXPECT_EQ(a.max_depth, 3);  // the default depth

  a = parse_antialiasing("adaptive:1:6");
  EXPECT_EQ(a.threshold, 1.f);
  EXPECT_EQ(a.max_depth, 6);

  a = parse_antialiasing("adaptive:.25:1");
  EXPECT_EQ(a.threshold, 0.25f);
  EXPECT_EQ(a.max_depth, 1);
}

TEST(AntiAliasingSpec, ToStringReadsBackTheSameSettings) {
  for (const char* spec : {"none", "regular:1", "regular:3", "jitter:2", "random:1", "random:17", "adaptive:0.1:3",
                           "adaptive:0.333:6", "adaptive:1:1", "adaptive:1e-05:2"}) {
    AntiAliasing a = parse_antialiasing(spec);
    EXPECT_EQ(to_string(a), spec);
    AntiAliasing b = parse_antialiasing(to_string(a));
    EXPECT_EQ(a.mode, b.mode);
    EXPECT_EQ(a.k, b.k);
    EXPECT_EQ(a.threshold, b.threshold);
    EXPECT_EQ(a.max_depth, b.max_depth);
  }
  EXPECT_EQ(to_string(parse_antialiasing("adaptive:0.1")), "adaptive:0.1:3");
  AntiAliasing odd;
  odd.mode = Mode::adaptive;
  odd.threshold = 0.1f + 1e-8f;  // not a short decimal: still round-trips
  EXPECT_EQ(parse_antialiasing(to_string(odd)).threshold, odd.threshold);
}

TEST(AntiAliasingSpec, RejectsEverythingElse) {
  for (const char* spec :
       {"", "None", "NONE", "none:1", "regular", "regular:", "regular:0", "regular:65", "regular:2:2", "regular: 2",
        "regular:+2", "regular:-1", "regular:2.0", "regular:0x4", "jitter:x", "jitter:99999999999", "random:0",
        "random:4097", "adaptive", "adaptive:0", "adaptive:-0.1", "adaptive:1.5", "adaptive:nan", "adaptive:inf",
        "adaptive:1e-50", "adaptive:0.1:0", "adaptive:0.1:7", "adaptive:0.1:", "adaptive:0.1:3:1", "adaptive:0.1x",
        "supersample:4", " none", "none "}) {
    try {
      parse_antialiasing(spec);
      ADD_FAILURE() << "accepted '" << spec << "'";
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), "");
      EXPECT_EQ(e.line(), 0);
      std::string expected = std::string("bad anti-aliasing '") + spec + "': expected none, regular:K, jitter:K";
      EXPECT_EQ(std::string(e.what()).substr(0, expected.size()), expected) << e.what();
    }
  }
}

}  // namespace
}  // namespace raystep
