// Binary ray and hit files, the exchange format between raystep, scripts and other ray tracers.
// .rays: no header, 32 bytes per ray, little-endian float32: origin x y z, direction x y z, tmin, tmax
// (tmax may be +inf); count = size / 32. .hits: no header, 8 bytes per ray: int32 primitive id (-1: miss),
// float32 t (+inf on a miss); the i-th hit answers the i-th ray.
//
// Values are stored bit for bit, so NaN and infinities round-trip exactly. A ray file may contain NaN values:
// they are accepted, and such a ray simply misses everything (the kernels reject NaN rays).
#pragma once

#include <string>
#include <vector>

#include "raystep/geometry/ray.h"
#include "raystep/scene/geometry.h"

namespace raystep {

constexpr size_t kRayRecordBytes = 32;
constexpr size_t kHitRecordBytes = 8;

// Throws InputError(path, 0, ...) if the file is missing, not a regular file, unreadable, or its size is not
// a multiple of 32 bytes ("size N is not a multiple of 32 bytes"). Memory used is bounded by the file's size.
std::vector<Ray> read_rays(const std::string& path);

// Written atomically (util/atomic_file.h); throws InputError naming the path on failure.
void write_rays(const std::string& path, const std::vector<Ray>& rays);

// Throws InputError as read_rays (multiple of 8 bytes), and for a primitive id below -1.
// The barycentrics of the returned hits are zero (the file does not store them).
std::vector<Hit> read_hits(const std::string& path);

// A miss (prim < 0) is always written as (-1, +inf), whatever its t. Written atomically.
void write_hits(const std::string& path, const std::vector<Hit>& hits);

}  // namespace raystep
