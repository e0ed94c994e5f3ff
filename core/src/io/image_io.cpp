#include "raystep/io/image_io.h"

#include <png.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <csetjmp>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>

#include "raystep/geometry/numerics.h"
#include "raystep/util/atomic_file.h"
#include "raystep/util/error.h"

namespace raystep {

namespace {

// Limits that keep a bad file from making us allocate without bound.
constexpr int kMaxSide = 1 << 16;
constexpr size_t kMaxPixels = size_t(1) << 28;

void check_image(const std::string& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0 || image.width > kMaxSide || image.height > kMaxSide ||
      image.pixels.size() != size_t(image.width) * size_t(image.height))
    throw InputError(path, 0, "cannot write an empty or inconsistent image (" + std::to_string(image.width) +
                                  " x " + std::to_string(image.height) + ")");
}

std::vector<uint8_t> read_whole_file(const std::string& path, size_t max_bytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, std::string("cannot open: ") + std::strerror(errno));
  in.seekg(0, std::ios::end);
  std::streamoff size = in.tellg();
  if (size < 0) throw InputError(path, 0, "cannot read");
  if (uint64_t(size) > max_bytes) throw InputError(path, 0, "file too large");
  in.seekg(0, std::ios::beg);
  std::vector<uint8_t> data(static_cast<size_t>(size));
  if (size > 0 && !in.read(reinterpret_cast<char*>(data.data()), size)) throw InputError(path, 0, "cannot read");
  return data;
}

// ---- PNG through libpng ----
// libpng reports errors by longjmp, which must not skip a C++ destructor: the functions that call setjmp
// hold only trivially destructible locals; their buffers belong to the caller.

struct PngError {
  char message[256];
};

void on_png_error(png_structp png, png_const_charp message) {
  auto* error = static_cast<PngError*>(png_get_error_ptr(png));
  std::snprintf(error->message, sizeof error->message, "%s", message);
  png_longjmp(png, 1);
}
void on_png_warning(png_structp, png_const_charp) {}

void png_append(png_structp png, png_bytep data, png_size_t length) {
  auto* out = static_cast<std::vector<uint8_t>*>(png_get_io_ptr(png));
  bool ok = true;
  try {
    out->insert(out->end(), data, data + length);
  } catch (...) {
    ok = false;
  }
  if (!ok) png_error(png, "out of memory");
}
void png_flush_nothing(png_structp) {}

bool encode_png(const uint8_t* rgb, int w, int h, std::vector<uint8_t>* out, PngError* error) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, error, on_png_error, on_png_warning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_set_write_fn(png, out, png_append, png_flush_nothing);
  png_set_IHDR(png, info, png_uint_32(w), png_uint_32(h), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
  png_write_info(png, info);
  for (int y = 0; y < h; ++y) png_write_row(png, rgb + size_t(y) * size_t(w) * 3);
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

struct PngSource {
  const uint8_t* data;
  size_t size, pos;
};

void png_take(png_structp png, png_bytep dst, png_size_t length) {
  auto* src = static_cast<PngSource*>(png_get_io_ptr(png));
  if (length > src->size - src->pos) png_error(png, "truncated file");
  std::memcpy(dst, src->data + src->pos, length);
  src->pos += length;
}

// Decodes into *pixels (3 bytes per pixel); *rows is scratch for the row pointers.
bool decode_png(PngSource* src, Rgb8Image* image, std::vector<png_bytep>* rows, PngError* error) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, error, on_png_error, on_png_warning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  png_set_user_limits(png, kMaxSide, kMaxSide);
  png_set_read_fn(png, src, png_take);
  png_read_info(png, info);
  // Transforms to 8-bit RGB: palette and low-bit grey expanded, 16 bit stripped, grey to RGB, alpha dropped.
  png_set_expand(png);
  png_set_strip_16(png);
  png_set_gray_to_rgb(png);
  png_set_strip_alpha(png);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  png_uint_32 w = png_get_image_width(png, info), h = png_get_image_height(png, info);
  if (size_t(w) * size_t(h) > kMaxPixels || png_get_rowbytes(png, info) != size_t(w) * 3)
    png_error(png, "unsupported image size or layout");
  image->width = int(w);
  image->height = int(h);
  image->rgb.resize(size_t(w) * size_t(h) * 3);
  rows->resize(h);
  for (png_uint_32 y = 0; y < h; ++y) (*rows)[y] = image->rgb.data() + size_t(y) * size_t(w) * 3;
  png_read_image(png, rows->data());
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

// ---- PFM ----

// Reads one whitespace-delimited header token starting at *pos; at most 32 characters.
std::string pfm_token(const std::string& path, const std::vector<uint8_t>& data, size_t* pos) {
  while (*pos < data.size() && std::isspace(data[*pos])) ++*pos;
  std::string token;
  while (*pos < data.size() && !std::isspace(data[*pos])) {
    token += char(data[*pos]);
    ++*pos;
    if (token.size() > 32) throw InputError(path, 0, "not a PFM file: header token too long");
  }
  if (token.empty()) throw InputError(path, 0, "not a PFM file: truncated header");
  return token;
}

int pfm_dimension(const std::string& path, const std::string& token) {
  long v = 0;
  for (char c : token) {
    if (c < '0' || c > '9') throw InputError(path, 0, "not a PFM file: bad size '" + token + "'");
    v = v * 10 + (c - '0');
    if (v > kMaxSide) throw InputError(path, 0, "PFM size too large: " + token);
  }
  if (v == 0) throw InputError(path, 0, "PFM size must be positive");
  return int(v);
}

}  // namespace

std::vector<uint8_t> png_bytes(const Image& image) {
  check_image("", image);
  std::vector<uint8_t> rgb(image.pixels.size() * 3);
  for (size_t i = 0; i < image.pixels.size(); ++i)
    for (int a = 0; a < 3; ++a) rgb[3 * i + a] = srgb_encode8(image.pixels[i][a]);
  std::vector<uint8_t> encoded;
  PngError error{};
  if (!encode_png(rgb.data(), image.width, image.height, &encoded, &error))
    throw InputError("", 0, std::string("cannot encode PNG: ") + error.message);
  return encoded;
}

void write_png(const std::string& path, const Image& image) {
  check_image(path, image);
  std::vector<uint8_t> encoded;
  try {
    encoded = png_bytes(image);
  } catch (const InputError& e) {
    throw InputError(path, 0, e.detail());
  }
  write_file_atomically(path, [&](std::ostream& out) {
    out.write(reinterpret_cast<const char*>(encoded.data()), std::streamsize(encoded.size()));
  });
}

Rgb8Image read_png_rgb8(const std::string& path) {
  std::vector<uint8_t> data = read_whole_file(path, size_t(1) << 30);
  PngSource src{data.data(), data.size(), 0};
  Rgb8Image image;
  std::vector<png_bytep> rows;
  PngError error{};
  if (data.size() < 8 || png_sig_cmp(data.data(), 0, 8) != 0) throw InputError(path, 0, "not a PNG file");
  if (!decode_png(&src, &image, &rows, &error))
    throw InputError(path, 0, std::string("bad PNG file: ") + error.message);
  return image;
}

Image read_png(const std::string& path) {
  Rgb8Image rgb8 = read_png_rgb8(path);
  Image image(rgb8.width, rgb8.height);
  for (size_t i = 0; i < image.pixels.size(); ++i)
    for (int a = 0; a < 3; ++a) image.pixels[i][a] = srgb_decode(rgb8.rgb[3 * i + a] / 255.f);
  return image;
}

void write_pfm(const std::string& path, const Image& image) {
  check_image(path, image);
  std::string header = "PF\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n-1.0\n";
  std::vector<uint8_t> body(image.pixels.size() * 12);
  size_t k = 0;
  for (int y = image.height - 1; y >= 0; --y)  // bottom row first
    for (int x = 0; x < image.width; ++x)
      for (int a = 0; a < 3; ++a) {
        uint32_t bits = float_to_bits(image.at(x, y)[a]);
        for (int byte = 0; byte < 4; ++byte) body[k++] = uint8_t(bits >> (8 * byte));  // little-endian
      }
  write_file_atomically(path, [&](std::ostream& out) {
    out << header;
    out.write(reinterpret_cast<const char*>(body.data()), std::streamsize(body.size()));
  });
}

Image read_pfm(const std::string& path) {
  std::vector<uint8_t> data = read_whole_file(path, size_t(kMaxPixels) * 12 + 1024);
  // Header: "PF" (colour) or "Pf" (grey), width, height, scale; then exactly one whitespace character.
  size_t pos = 0;
  std::string magic = pfm_token(path, data, &pos);
  if (magic != "PF" && magic != "Pf") throw InputError(path, 0, "not a PFM file (magic '" + magic + "')");
  int channels = magic == "PF" ? 3 : 1;
  int width = pfm_dimension(path, pfm_token(path, data, &pos));
  int height = pfm_dimension(path, pfm_token(path, data, &pos));
  std::string scale_text = pfm_token(path, data, &pos);
  char* end = nullptr;
  double scale = std::strtod(scale_text.c_str(), &end);
  if (end != scale_text.c_str() + scale_text.size() || !std::isfinite(scale) || scale == 0.0)
    throw InputError(path, 0, "bad PFM scale '" + scale_text + "'");
  if (pos >= data.size() || !std::isspace(data[pos])) throw InputError(path, 0, "truncated PFM header");
  ++pos;
  size_t expected = size_t(width) * size_t(height) * size_t(channels) * 4;
  if (size_t(width) * size_t(height) > kMaxPixels || data.size() - pos != expected)
    throw InputError(path, 0, "PFM data size " + std::to_string(data.size() - pos) + " bytes, expected " +
                                  std::to_string(expected) + " for " + std::to_string(width) + " x " +
                                  std::to_string(height));

  bool little_endian = scale < 0;
  Image image(width, height);
  const uint8_t* p = data.data() + pos;
  for (int y = height - 1; y >= 0; --y)  // bottom row first
    for (int x = 0; x < width; ++x) {
      glm::vec3 c;
      for (int a = 0; a < channels; ++a, p += 4) {
        uint32_t bits = 0;
        for (int byte = 0; byte < 4; ++byte)
          bits |= uint32_t(p[little_endian ? byte : 3 - byte]) << (8 * byte);
        c[a] = bits_to_float(bits);
      }
      image.at(x, y) = channels == 3 ? c : glm::vec3(c[0]);
    }
  return image;
}

}  // namespace raystep
