// libFuzzer harness for the OBJ reader (io/obj.h), through its from-text entry point.
#include <cstdint>
#include <string>

#include "contract.h"
#include "raystep/io/obj.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  raystep::fuzz::expect_contract("obj", "fuzz.obj", raystep::fuzz::line_count(text),
                                 [&] { raystep::parse_obj(text, "fuzz.obj"); });
  return 0;
}
