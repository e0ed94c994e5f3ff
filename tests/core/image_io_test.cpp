// Image files: PFM round trip bit for bit, the PFM layout, bad PFM and PNG files, PNG sRGB codes, and
// atomic writes.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>
#include <cmath>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include "raystep/io/image_io.h"
#include "raystep/util/atomic_file.h"
#include "raystep/util/error.h"

namespace raystep {
namespace {

namespace fs = std::filesystem;

// A fresh, empty directory per test.
class ImageIo : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("raystep_image_io_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  void write_bytes(const std::string& name, const std::string& bytes) const {
    std::ofstream out(path(name), std::ios::binary);
    out << bytes;
  }
  std::string read_bytes(const std::string& name) const {
    std::ifstream in(path(name), std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
  size_t file_count() const { return size_t(std::distance(fs::directory_iterator(dir_), {})); }

  fs::path dir_;
};

uint32_t bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  return u;
}

Image awkward_image() {
  // Not square, with values a text format would round: subnormal, -0, huge, tiny, non-representable.
  Image img(3, 2);
  img.at(0, 0) = glm::vec3(0.1f, -0.f, 1e-40f);
  img.at(1, 0) = glm::vec3(3.4e38f, -2.5f, 1.f / 3.f);
  img.at(2, 0) = glm::vec3(std::numeric_limits<float>::infinity(), 0.f, 7.f);
  img.at(0, 1) = glm::vec3(1.f, 2.f, 3.f);
  img.at(1, 1) = glm::vec3(std::nextafter(1.f, 2.f), 1e-7f, 123456.789f);
  img.at(2, 1) = glm::vec3(0.5f);
  return img;
}

TEST_F(ImageIo, PfmRoundTripIsBitExact) {
  Image img = awkward_image();
  write_pfm(path("a.pfm"), img);
  Image back = read_pfm(path("a.pfm"));
  ASSERT_EQ(back.width, 3);
  ASSERT_EQ(back.height, 2);
  for (size_t i = 0; i < img.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) EXPECT_EQ(bits(back.pixels[i][c]), bits(img.pixels[i][c])) << i << " " << c;
}

TEST_F(ImageIo, PfmLayoutLittleEndianBottomRowFirst) {
  write_pfm(path("a.pfm"), awkward_image());
  std::string bytes = read_bytes("a.pfm");
  const std::string header = "PF\n3 2\n-1.0\n";
  ASSERT_EQ(bytes.size(), header.size() + 3 * 2 * 12);
  EXPECT_EQ(bytes.substr(0, header.size()), header);
  // The first pixel in the file is the bottom-left one, (1, 2, 3); 1.0f = 0x3f800000 little-endian.
  EXPECT_EQ(bytes.substr(header.size(), 4), std::string("\x00\x00\x80\x3f", 4));
}

std::string big_endian_floats(std::initializer_list<float> values) {
  std::string s;
  for (float v : values) {
    uint32_t u = bits(v);
    for (int b = 3; b >= 0; --b) s += char((u >> (8 * b)) & 0xff);
  }
  return s;
}

TEST_F(ImageIo, PfmReadsBigEndianAndGreyscale) {
  // Positive scale: big-endian. Rows bottom to top: the file's first pixel is (0, 1).
  write_bytes("be.pfm", "PF\n1 2\n1.0\n" + big_endian_floats({1.f, 2.f, 3.f, 4.f, 5.f, 6.f}));
  Image be = read_pfm(path("be.pfm"));
  EXPECT_EQ(be.at(0, 1), glm::vec3(1.f, 2.f, 3.f));
  EXPECT_EQ(be.at(0, 0), glm::vec3(4.f, 5.f, 6.f));
  write_bytes("grey.pfm", "Pf 2 1 1\n" + big_endian_floats({0.25f, 8.f}));
  Image grey = read_pfm(path("grey.pfm"));
  EXPECT_EQ(grey.at(0, 0), glm::vec3(0.25f));
  EXPECT_EQ(grey.at(1, 0), glm::vec3(8.f));
}

TEST_F(ImageIo, BadPfmFilesThrowInputError) {
  const std::string pixel = big_endian_floats({1.f, 2.f, 3.f});
  const std::pair<const char*, std::string> bad[] = {
      {"empty.pfm", ""},
      {"magic.pfm", "P6\n1 1\n-1.0\n" + pixel},
      {"truncated_header.pfm", "PF\n1 1\n"},
      {"short.pfm", "PF\n1 1\n-1.0\n" + pixel.substr(0, 11)},
      {"long.pfm", "PF\n1 1\n-1.0\n" + pixel + "x"},
      {"zero.pfm", "PF\n0 1\n-1.0\n"},
      {"negative.pfm", "PF\n-1 1\n-1.0\n" + pixel},
      {"letters.pfm", "PF\n1x 1\n-1.0\n" + pixel},
      {"huge.pfm", "PF\n99999999999999999999 99999999\n-1.0\n" + pixel},  // must not allocate
      {"huge2.pfm", "PF\n60000 60000\n-1.0\n" + pixel},
      {"scale0.pfm", "PF\n1 1\n0\n" + pixel},
      {"scalenan.pfm", "PF\n1 1\nnan\n" + pixel},
      {"scaletext.pfm", "PF\n1 1\n-1.0abc\n" + pixel},
      {"notoken.pfm", "PF\n1 1\n-1.0"},
  };
  for (const auto& [name, content] : bad) {
    write_bytes(name, content);
    EXPECT_THROW(read_pfm(path(name)), InputError) << name;
  }
  EXPECT_THROW(read_pfm(path("missing.pfm")), InputError);
  try {
    read_pfm(path("short.pfm"));
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path("short.pfm"));  // the message names the file
  }
}

TEST_F(ImageIo, PngStoresSrgbCodes) {
  Image img(4, 2);
  const float linear[8] = {0.f, 1.f, 0.5f, 0.2f, 0.001f, 2.f, -1.f, std::nanf("")};
  for (int i = 0; i < 8; ++i) img.pixels[size_t(i)] = glm::vec3(linear[i], 0.f, 1.f);
  write_png(path("a.png"), img);
  Rgb8Image back = read_png_rgb8(path("a.png"));
  ASSERT_EQ(back.width, 4);
  ASSERT_EQ(back.height, 2);
  // sRGB: 1.055 v^(1/2.4) - 0.055 above 0.0031308, 12.92 v below; clamped; NaN -> 0.
  const int expected[8] = {0, 255, 188, 124, 3, 255, 0, 0};
  for (int i = 0; i < 8; ++i) {
    EXPECT_EQ(back.at(i % 4, i / 4)[0], expected[i]) << "linear " << linear[i];
    EXPECT_EQ(back.at(i % 4, i / 4)[1], 0);
    EXPECT_EQ(back.at(i % 4, i / 4)[2], 255);
  }
  // read_png decodes to linear: within the 8-bit quantisation.
  Image lin = read_png(path("a.png"));
  EXPECT_NEAR(lin.at(2, 0).x, 0.5f, 0.003f);
  EXPECT_EQ(lin.at(1, 0).x, 1.f);
}

TEST_F(ImageIo, SrgbCurveInverts) {
  for (float v = 0.f; v <= 1.f; v += 0.01f) EXPECT_NEAR(srgb_decode(srgb_encode(v)), v, 1e-5f);
  EXPECT_NEAR(srgb_encode(0.0031308f), 0.04045f, 1e-5f);  // the two pieces meet
  EXPECT_EQ(srgb_encode8(0.5f), 188);
}

TEST_F(ImageIo, BadPngFilesThrowInputError) {
  write_bytes("garbage.png", "definitely not a png");
  EXPECT_THROW(read_png_rgb8(path("garbage.png")), InputError);
  Image img(5, 5, glm::vec3(0.3f));
  write_png(path("good.png"), img);
  std::string bytes = read_bytes("good.png");
  write_bytes("truncated.png", bytes.substr(0, bytes.size() / 2));
  EXPECT_THROW(read_png_rgb8(path("truncated.png")), InputError);
  EXPECT_THROW(read_png(path("missing.png")), InputError);
}

TEST_F(ImageIo, WritesAreAtomic) {
  Image img(2, 2, glm::vec3(0.5f));
  write_png(path("a.png"), img);
  write_pfm(path("a.pfm"), img);
  write_png(path("a.png"), img);  // overwrite in place
  EXPECT_EQ(file_count(), 2u);    // no temporary file left beside the outputs
  // Unwritable target: InputError, and nothing left behind.
  EXPECT_THROW(write_png(path("no/such/dir/a.png"), img), InputError);
  EXPECT_THROW(write_pfm(path("no/such/dir/a.pfm"), img), InputError);
  EXPECT_EQ(file_count(), 2u);
  // An empty image is refused before anything is written.
  EXPECT_THROW(write_png(path("empty.png"), Image()), InputError);
  EXPECT_THROW(write_pfm(path("empty.pfm"), Image(2, 0)), InputError);
  EXPECT_EQ(file_count(), 2u);
}

// Ctrl-C in the middle of a write: the temporary file goes, the target stays as it was, and the process ends
// by the signal. In a child process, so that the signal ends only the child.
TEST_F(ImageIo, InterruptedWriteLeavesNoTemporaryFile) {
  const std::string target = path("out.txt");
  { std::ofstream(target) << "before"; }
  for (int sig : {SIGINT, SIGTERM}) {
    pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      remove_temporary_files_on_signals();
      AtomicFile file(target);
      std::ofstream(file.temp_path()) << "half";
      ::raise(sig);
      ::_exit(3);  // not reached: the signal ends the process
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(WIFSIGNALED(status)) << "status " << status;
    EXPECT_EQ(WTERMSIG(status), sig);
    EXPECT_EQ(file_count(), 1u) << "signal " << sig;  // only out.txt: no out.txt.tmp.PID
    std::ifstream in(target);
    std::string text;
    in >> text;
    EXPECT_EQ(text, "before");
  }
}

}  // namespace
}  // namespace raystep
