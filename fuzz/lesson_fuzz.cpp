// libFuzzer harness for the lesson reader (lesson/lesson.h), from text. The lesson is named as a file of the
// scratch folder, so that "scene: scene.json" names a scene there.
#include <cstdint>
#include <string>

#include "contract.h"
#include "raystep/lesson/lesson.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string path = raystep::fuzz::scratch_folder() + "/fuzz-lesson.md";
  const std::string text(reinterpret_cast<const char*>(data), size);
  raystep::fuzz::expect_contract("lesson", path, raystep::fuzz::line_count(text),
                                 [&] { raystep::parse_lesson_text(text, path); });
  return 0;
}
