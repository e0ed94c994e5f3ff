// ray_files.h: .rays and .hits round-trip bit for bit (infinities, NaN payloads, -0, denormals), the byte
// layout is little-endian float32 as documented, and bad files throw InputError naming the file.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "raystep/geometry/bounds.h"
#include "raystep/geometry/triangle.h"
#include "raystep/io/ray_files.h"
#include "raystep/util/error.h"

namespace raystep {
namespace {

namespace fs = std::filesystem;

class RayFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fs::path(::testing::TempDir()) /
        ("raystep_ray_files_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  void write_bytes(const std::string& p, const std::string& bytes) const {
    std::ofstream(p, std::ios::binary) << bytes;
  }
  std::string read_bytes(const std::string& p) const {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
  fs::path dir_;
};

std::vector<Ray> awkward_rays() {
  std::vector<Ray> rays(5);
  rays[0].origin = glm::vec3(1.f, -2.f, 3.5f);
  rays[0].direction = glm::vec3(0.f, -0.f, 1.f);
  rays[1].origin = glm::vec3(std::numeric_limits<float>::denorm_min(), -1e30f, 1e-30f);
  rays[1].tmin = 0.25f;
  rays[1].tmax = 7.f;
  rays[2].origin = glm::vec3(bits_to_float(0x7fc01234u), 0.f, 0.f);     // NaN with a payload
  rays[2].direction = glm::vec3(bits_to_float(0xffc00001u), 1.f, 0.f);  // negative NaN
  rays[3].tmax = kInfinity;
  rays[3].tmin = -kInfinity;
  rays[4].direction = glm::vec3(-kInfinity, std::numeric_limits<float>::max(), -0.f);
  return rays;
}

void expect_same_bits(const Ray& a, const Ray& b) {
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(float_to_bits(a.origin[k]), float_to_bits(b.origin[k]));
    EXPECT_EQ(float_to_bits(a.direction[k]), float_to_bits(b.direction[k]));
  }
  EXPECT_EQ(float_to_bits(a.tmin), float_to_bits(b.tmin));
  EXPECT_EQ(float_to_bits(a.tmax), float_to_bits(b.tmax));
}

TEST_F(RayFiles, RaysRoundTripBitExact) {
  std::vector<Ray> rays = awkward_rays();
  write_rays(path("a.rays"), rays);
  EXPECT_EQ(fs::file_size(path("a.rays")), rays.size() * 32);
  std::vector<Ray> back = read_rays(path("a.rays"));
  ASSERT_EQ(back.size(), rays.size());
  for (size_t i = 0; i < rays.size(); ++i) expect_same_bits(rays[i], back[i]);
  // Nothing else was left in the directory (no temporary file).
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 1);
}

// The documented layout: little-endian float32 o.xyz, d.xyz, tmin, tmax; no header.
TEST_F(RayFiles, ByteLayoutIsLittleEndianFloat32) {
  Ray r;
  r.origin = glm::vec3(1.f, 2.f, -2.f);
  r.direction = glm::vec3(0.5f, 0.f, -0.f);
  r.tmin = 0.f;
  r.tmax = kInfinity;
  write_rays(path("one.rays"), {r});
  std::string bytes = read_bytes(path("one.rays"));
  ASSERT_EQ(bytes.size(), 32u);
  const uint32_t expected[8] = {0x3f800000u, 0x40000000u, 0xc0000000u, 0x3f000000u,
                                0x00000000u, 0x80000000u, 0x00000000u, 0x7f800000u};
  for (int i = 0; i < 8; ++i)
    for (int b = 0; b < 4; ++b)
      EXPECT_EQ(uint8_t(bytes[4 * i + b]), uint8_t(expected[i] >> (8 * b))) << "float " << i << " byte " << b;
  // And a hand-made file reads back: 1.0f = 00 00 80 3f.
  std::string hand(32, '\0');
  hand[2] = char(0x80);
  hand[3] = char(0x3f);
  write_bytes(path("hand.rays"), hand);
  std::vector<Ray> rays = read_rays(path("hand.rays"));
  ASSERT_EQ(rays.size(), 1u);
  EXPECT_EQ(rays[0].origin.x, 1.f);
  EXPECT_EQ(rays[0].tmax, 0.f);
}

TEST_F(RayFiles, EmptyFileHasNoRays) {
  write_bytes(path("empty.rays"), "");
  EXPECT_TRUE(read_rays(path("empty.rays")).empty());
  write_rays(path("none.rays"), {});
  EXPECT_EQ(fs::file_size(path("none.rays")), 0u);
}

TEST_F(RayFiles, SizeNotAMultipleOf32IsAnInputError) {
  write_bytes(path("bad.rays"), std::string(33, 'x'));
  try {
    read_rays(path("bad.rays"));
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path("bad.rays"));
    EXPECT_EQ(e.line(), 0);
    EXPECT_EQ(e.detail(), "size 33 is not a multiple of 32 bytes");
  }
  write_bytes(path("short.rays"), std::string(31, 'x'));
  EXPECT_THROW(read_rays(path("short.rays")), InputError);
}

TEST_F(RayFiles, MissingFileAndDirectoryAreInputErrors) {
  try {
    read_rays(path("nope.rays"));
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path("nope.rays"));
  }
  EXPECT_THROW(read_rays(dir_.string()), InputError);
  EXPECT_THROW(read_hits(path("nope.hits")), InputError);
  // Writing where the directory does not exist: an InputError, and no file appears.
  EXPECT_THROW(write_rays(path("no/such/dir/a.rays"), awkward_rays()), InputError);
  EXPECT_THROW(write_hits(path("no/such/dir/a.hits"), {}), InputError);
  EXPECT_FALSE(fs::exists(path("no")));
}

// A NaN ray is valid in a file; it simply misses everything.
TEST_F(RayFiles, NaNRaysFromAFileMiss) {
  std::vector<Ray> rays = awkward_rays();
  write_rays(path("nan.rays"), rays);
  std::vector<Ray> back = read_rays(path("nan.rays"));
  const Ray& r = back[2];
  EXPECT_TRUE(std::isnan(r.origin.x));
  EXPECT_FALSE(intersect_slabs(Bounds3(glm::vec3(-1e30f), glm::vec3(1e30f)), r));
  TriangleHit h;
  EXPECT_FALSE(intersect_triangle(r, glm::vec3(-1e3f, -1e3f, 0.f), glm::vec3(1e3f, -1e3f, 0.f),
                                  glm::vec3(0.f, 1e3f, 0.f), &h));
}

TEST_F(RayFiles, HitsRoundTripAndMissesAreNormalised) {
  std::vector<Hit> hits(4);
  hits[0].prim = 0;
  hits[0].t = 1.5f;
  hits[1].prim = 2147483647;
  hits[1].t = std::numeric_limits<float>::denorm_min();
  hits[2].prim = -1;
  hits[2].t = 3.f;  // a miss with a stale t: written as +inf
  hits[3].prim = 7;
  hits[3].t = bits_to_float(0x7fc0beefu);
  write_hits(path("a.hits"), hits);
  EXPECT_EQ(fs::file_size(path("a.hits")), 32u);
  std::string bytes = read_bytes(path("a.hits"));
  EXPECT_EQ(bytes.substr(16, 4), std::string(4, char(0xff)));  // int32 -1, little-endian
  std::vector<Hit> back = read_hits(path("a.hits"));
  ASSERT_EQ(back.size(), 4u);
  EXPECT_EQ(back[0].prim, 0);
  EXPECT_EQ(back[0].t, 1.5f);
  EXPECT_EQ(back[1].prim, 2147483647);
  EXPECT_EQ(float_to_bits(back[1].t), float_to_bits(hits[1].t));
  EXPECT_EQ(back[2].prim, -1);
  EXPECT_EQ(back[2].t, kInfinity);
  EXPECT_FALSE(back[2].found());
  EXPECT_EQ(float_to_bits(back[3].t), 0x7fc0beefu);
}

TEST_F(RayFiles, BadHitFilesAreInputErrors) {
  write_bytes(path("odd.hits"), std::string(12, '\0'));
  EXPECT_THROW(read_hits(path("odd.hits")), InputError);
  std::string record(8, '\0');
  record[0] = char(0xfe);  // int32 -2
  record[1] = record[2] = record[3] = char(0xff);
  write_bytes(path("neg.hits"), std::string(8, '\0') + record);
  try {
    read_hits(path("neg.hits"));
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path("neg.hits"));
    EXPECT_NE(e.detail().find("record 1"), std::string::npos) << e.detail();
  }
}

// Many rays: the chunked reader crosses its buffer boundaries without losing or reordering any.
TEST_F(RayFiles, LargeFileRoundTrips) {
  std::vector<Ray> rays(10007);
  for (size_t i = 0; i < rays.size(); ++i) {
    rays[i].origin = glm::vec3(float(i), -float(i), 0.5f * float(i));
    rays[i].tmax = float(i);
  }
  write_rays(path("big.rays"), rays);
  std::vector<Ray> back = read_rays(path("big.rays"));
  ASSERT_EQ(back.size(), rays.size());
  for (size_t i = 0; i < rays.size(); ++i) ASSERT_EQ(back[i].origin.y, -float(i));
  EXPECT_EQ(back.back().tmax, 10006.f);
}

}  // namespace
}  // namespace raystep
