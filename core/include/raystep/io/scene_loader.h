// Scenes from files: a JSON scene (the format is docs/scene-format.md) or a bare OBJ mesh, which gets a
// camera that frames it, one light at the eye and the default material, so any mesh renders at once.
// Every mistake in a file throws InputError with the file, the line and the path of the offending value:
//   scene.json:12: objects[2].radius: expected a positive number
#pragma once

#include <string>

#include "raystep/geometry/bounds.h"
#include "raystep/scene/scene.h"

namespace raystep {

// A ".obj" file (any case) is read as a bare mesh, anything else as a JSON scene. Sets Scene::path.
Scene load_scene(const std::string& path);

// A JSON scene from text; `path` names the file in messages, and mesh files are found relative to its folder.
Scene parse_scene(const std::string& json_text, const std::string& path);

// The mesh alone: default material, one point light at the eye, camera_framing(mesh bounds).
Scene scene_from_mesh(const std::string& obj_path);

// A pinhole camera (vertical fov_deg) that looks at the centre of the bounds from the front-right-above
// diagonal (+x, +y, +z), far enough that the whole bounding sphere is in view for any aspect >= 1.
Camera camera_framing(const Bounds3& bounds, float fov_deg = 40.f);

}  // namespace raystep
