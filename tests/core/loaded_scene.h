// A shipped scene (scenes/NAME in the source tree) loaded, with an acceleration structure built over it: what
// the pixel-sample and pixel-trace tests render and trace. Needs RAYSTEP_SOURCE_DIR.
#pragma once

#include <memory>
#include <string>

#include "raystep/accel/accelerator.h"
#include "raystep/scene/scene.h"
#include "raystep/io/scene_loader.h"

namespace raystep::test {

struct LoadedScene {
  Scene scene;
  std::unique_ptr<Accelerator> accel;
  explicit LoadedScene(const std::string& name, const char* structure = "grid")
      : scene(load_scene(std::string(RAYSTEP_SOURCE_DIR) + "/scenes/" + name)),
        accel(make_accelerator(structure)) {
    accel->build(scene.geometry);
  }
};

}  // namespace raystep::test
