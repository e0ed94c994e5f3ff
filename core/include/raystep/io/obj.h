// Wavefront OBJ meshes, read with tinyobjloader. Only what a ray tracer needs: v, vn and f lines (o, g,
// usemtl, vt... are read past). The primitive id contract: triangles in the order the file lists its
// faces, a polygon v0..vn split as the fan (v0, vi, vi+1); OBJ's negative (relative) indices are allowed.
#pragma once

#include <string>

#include "raystep/scene/triangle_mesh.h"

namespace raystep {

// A face keeps its vertex normals when every one of its vertices names a non-zero normal; otherwise
// it has none (normal_triangles[i] = kNoNormal), and normal_triangles is empty when no face has them.
// Throws InputError(path, line, ...) for a missing or unreadable file, a malformed number or index,
// NaN or Inf coordinates, an index out of range or 0, a face of fewer than 3 or more than 255 vertices,
// and a file with no faces. Degenerate (zero-area) triangles are kept.
TriangleMesh load_obj(const std::string& path);

// The same from text in memory; `name` stands for the file in error messages.
TriangleMesh parse_obj(const std::string& text, const std::string& name);

}  // namespace raystep
