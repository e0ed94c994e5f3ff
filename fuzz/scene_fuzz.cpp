// libFuzzer harness for the JSON scene reader (io/scene_loader.h). The scene is named as a file of the
// scratch folder, so that "file": "mesh.obj" finds a mesh there (and the mesh path is exercised).
#include <cstdint>
#include <string>

#include "contract.h"
#include "raystep/io/scene_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string path = raystep::fuzz::scratch_folder() + "/fuzz-scene.json";
  const std::string text(reinterpret_cast<const char*>(data), size);
  raystep::fuzz::expect_contract("scene", path, raystep::fuzz::line_count(text),
                                 [&] { raystep::parse_scene(text, path); });
  return 0;
}
