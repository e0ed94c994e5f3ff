#include "raystep/io/ray_files.h"

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <ostream>

#include "raystep/geometry/numerics.h"
#include "raystep/util/atomic_file.h"
#include "raystep/util/error.h"

namespace raystep {
namespace {

// Little-endian encoding by shifts, so the files are the same on any host.
uint32_t load_u32(const unsigned char* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}
float load_f32(const unsigned char* p) {
  return bits_to_float(load_u32(p));
}
void store_u32(unsigned char* p, uint32_t u) {
  p[0] = uint8_t(u);
  p[1] = uint8_t(u >> 8);
  p[2] = uint8_t(u >> 16);
  p[3] = uint8_t(u >> 24);
}
void store_f32(unsigned char* p, float f) {
  store_u32(p, float_to_bits(f));
}

// Reads a headerless file of fixed-size records in chunks; decode(record, index) is called for each.
// The record count comes from the size of a regular file, so nothing is allocated beyond what the file holds.
template <typename Decode>
size_t read_records(const std::string& path, size_t record_bytes, Decode decode) {
  // Checked before opening: opening a FIFO would block, and a device or directory has no meaningful size.
  std::error_code ec;
  std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) throw InputError(path, 0, "cannot open: no such file");
  if (!std::filesystem::is_regular_file(status)) throw InputError(path, 0, "not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, std::string("cannot open: ") + std::strerror(errno));
  uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(path, 0, "cannot read the size: " + ec.message());
  if (size % record_bytes != 0)
    throw InputError(
        path, 0,
        "size " + std::to_string(size) + " is not a multiple of " + std::to_string(record_bytes) + " bytes");
  size_t count = size_t(size / record_bytes);
  const size_t chunk_records = 4096;
  std::vector<unsigned char> buffer(chunk_records * record_bytes);
  for (size_t done = 0; done < count;) {
    size_t n = std::min(chunk_records, count - done);
    in.read(reinterpret_cast<char*>(buffer.data()), std::streamsize(n * record_bytes));
    if (size_t(in.gcount()) != n * record_bytes)
      throw InputError(path, 0, "file ended early (truncated while reading?)");
    for (size_t i = 0; i < n; ++i) decode(buffer.data() + i * record_bytes, done + i);
    done += n;
  }
  return count;
}

size_t record_count(const std::string& path, size_t record_bytes) {
  std::error_code ec;
  uintmax_t size = std::filesystem::file_size(path, ec);
  return ec ? 0 : size_t(size / record_bytes);
}

}  // namespace

std::vector<Ray> read_rays(const std::string& path) {
  std::vector<Ray> rays;
  rays.reserve(record_count(path, kRayRecordBytes));  // bounded by the file's size
  read_records(path, kRayRecordBytes, [&](const unsigned char* p, size_t) {
    Ray r;
    r.origin = glm::vec3(load_f32(p), load_f32(p + 4), load_f32(p + 8));
    r.direction = glm::vec3(load_f32(p + 12), load_f32(p + 16), load_f32(p + 20));
    r.tmin = load_f32(p + 24);
    r.tmax = load_f32(p + 28);
    rays.push_back(r);
  });
  return rays;
}

void write_rays(const std::string& path, const std::vector<Ray>& rays) {
  write_file_atomically(path, [&](std::ostream& out) {
    unsigned char record[kRayRecordBytes];
    for (const Ray& r : rays) {
      for (int k = 0; k < 3; ++k) store_f32(record + 4 * k, r.origin[k]);
      for (int k = 0; k < 3; ++k) store_f32(record + 12 + 4 * k, r.direction[k]);
      store_f32(record + 24, r.tmin);
      store_f32(record + 28, r.tmax);
      out.write(reinterpret_cast<const char*>(record), sizeof record);
    }
  });
}

std::vector<Hit> read_hits(const std::string& path) {
  std::vector<Hit> hits;
  hits.reserve(record_count(path, kHitRecordBytes));
  read_records(path, kHitRecordBytes, [&](const unsigned char* p, size_t index) {
    Hit h;
    h.prim = int32_t(load_u32(p));
    h.t = load_f32(p + 4);
    if (h.prim < -1)
      throw InputError(
          path, 0,
          "record " + std::to_string(index) + ": primitive id " + std::to_string(h.prim) + " is below -1");
    hits.push_back(h);
  });
  return hits;
}

void write_hits(const std::string& path, const std::vector<Hit>& hits) {
  write_file_atomically(path, [&](std::ostream& out) {
    unsigned char record[kHitRecordBytes];
    for (const Hit& h : hits) {
      bool miss = h.prim < 0;
      store_u32(record, uint32_t(miss ? int32_t(-1) : h.prim));
      store_f32(record + 4, miss ? kInfinity : h.t);
      out.write(reinterpret_cast<const char*>(record), sizeof record);
    }
  });
}

}  // namespace raystep
