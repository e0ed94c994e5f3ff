// The image layout and the sample-count map's colour ramp.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "raystep/io/image_io.h"
#include "raystep/render/image.h"

namespace raystep {
namespace {

TEST(Image, RowMajorTopRowFirst) {
  Image img(3, 2, glm::vec3(0.25f));
  ASSERT_EQ(img.pixels.size(), 6u);
  EXPECT_EQ(img.at(2, 1), glm::vec3(0.25f));
  img.at(2, 0) = glm::vec3(1.f, 2.f, 3.f);  // top-right
  img.at(0, 1) = glm::vec3(4.f);            // bottom-left
  EXPECT_EQ(img.pixels[2], glm::vec3(1.f, 2.f, 3.f));
  EXPECT_EQ(img.pixels[3], glm::vec3(4.f));
}

float luminance(const glm::vec3& c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

TEST(Image, ViridisEndsAndMonotoneLuminance) {
  // The end stops #440154 and #fde725 come back as their 8-bit codes.
  EXPECT_EQ(srgb_encode8(viridis(0.f).x), 68);
  EXPECT_EQ(srgb_encode8(viridis(0.f).z), 84);
  EXPECT_EQ(srgb_encode8(viridis(1.f).x), 253);
  EXPECT_EQ(srgb_encode8(viridis(1.f).y), 231);
  EXPECT_EQ(viridis(-3.f), viridis(0.f));
  EXPECT_EQ(viridis(std::nanf("")), viridis(0.f));
  EXPECT_EQ(viridis(7.f), viridis(1.f));
  // Perceptual: brightness rises all the way.
  for (int i = 0; i < 100; ++i) EXPECT_LT(luminance(viridis(i / 100.f)), luminance(viridis((i + 1) / 100.f)));
}

TEST(Image, SampleCountMap) {
  std::vector<uint32_t> counts = {4, 4, 16, 64, 4, 0};
  uint32_t max_count = 0;
  Image map = sample_count_image(counts, 3, 2, &max_count);
  EXPECT_EQ(max_count, 64u);
  EXPECT_EQ(map.width, 3);
  EXPECT_EQ(map.height, 2);
  EXPECT_EQ(map.at(0, 1), viridis(1.f));  // the 64
  EXPECT_EQ(map.at(2, 0), viridis(0.25f));
  EXPECT_EQ(map.at(2, 1), viridis(0.f));
  EXPECT_LT(luminance(map.at(0, 0)), luminance(map.at(2, 0)));
  EXPECT_THROW(sample_count_image(counts, 2, 2, nullptr), std::invalid_argument);
  // All zero: no division by zero.
  Image zeros = sample_count_image(std::vector<uint32_t>(4, 0), 2, 2, &max_count);
  EXPECT_EQ(max_count, 0u);
  EXPECT_EQ(zeros.at(1, 1), viridis(0.f));
}

}  // namespace
}  // namespace raystep
