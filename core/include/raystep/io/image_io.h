// Image files. PNG: 8-bit sRGB (IEC 61966-2-1 transfer curve, clamped to [0, 1]) through libpng.
// PFM: the Portable Float Map (Debevec's HDR format): "PF\n<w> <h>\n<scale>\n", then float RGB rows
// from the bottom row up; a negative scale means little-endian. Every write is atomic (util/atomic_file.h);
// every read of a bad file throws InputError naming it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "raystep/render/image.h"

namespace raystep {

void write_png(const std::string& path, const Image& image);
// The same PNG file's bytes, in memory (a page's inlined picture). Throws InputError("", 0, ...) as write_png.
std::vector<uint8_t> png_bytes(const Image& image);
// Little-endian (scale -1), exact float bits: read_pfm(write_pfm(img)) == img bit for bit.
void write_pfm(const std::string& path, const Image& image);
// Accepts colour ("PF") and greyscale ("Pf", expanded to RGB) maps of either byte order.
Image read_pfm(const std::string& path);

// The 8-bit sRGB codes of a PNG (any colour type, expanded to RGB; 16-bit reduced to 8, alpha dropped).
struct Rgb8Image {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;  // 3 per pixel, top row first
  const uint8_t* at(int x, int y) const { return &rgb[3 * (size_t(y) * size_t(width) + size_t(x))]; }
};
Rgb8Image read_png_rgb8(const std::string& path);
// The same, decoded to linear RGB.
Image read_png(const std::string& path);

}  // namespace raystep
