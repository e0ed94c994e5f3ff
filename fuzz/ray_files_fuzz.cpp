// libFuzzer harness for the binary .rays and .hits readers (io/ray_files.h), which take a path only. Bit
// patterns matter here (NaN, infinities, ids below -1), so the input is the file itself.
#include <cstdint>
#include <string>

#include "contract.h"
#include "raystep/io/ray_files.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string rays = raystep::fuzz::write_input("fuzz.rays", data, size);
  raystep::fuzz::expect_contract("rays", rays, 0, [&] { raystep::read_rays(rays); });
  const std::string hits = raystep::fuzz::write_input("fuzz.hits", data, size);
  raystep::fuzz::expect_contract("hits", hits, 0, [&] { raystep::read_hits(hits); });
  return 0;
}
