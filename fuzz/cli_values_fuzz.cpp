// libFuzzer harness for the command line's hand-typed values: --size, --ray/--pixel/--grid-res number lists,
// --accel name lists, --densities (cli/value_parsers.h), and the core's --aa, --bsp-directions and --heatmap
// specs. The first byte picks the parser; the rest is the value. A refusal must name the option.
#include <cstdint>
#include <string>

#include "../cli/value_parsers.h"
#include "contract.h"
#include "raystep/accel/bsp_build.h"
#include "raystep/scene/antialiasing_spec.h"
#include "raystep/trace/heatmap.h"

using raystep::fuzz::expect_contract;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const std::string value(reinterpret_cast<const char*>(data) + 1, size - 1);
  int w = 0, h = 0;
  switch (data[0] % 8) {
    case 0:
      expect_contract("--size", "--size", 0, [&] { raystep::cli::parse_size(value, &w, &h); });
      break;
    case 1:
      // Six numbers, or in the plane of a 2D scene (bit 3 of the first byte) also four.
      expect_contract("--ray", "--ray", 0, [&] { raystep::cli::parse_ray(value, (data[0] >> 3) & 1); });
      break;
    case 2:
      expect_contract("--pixel", "--pixel", 0, [&] { raystep::cli::parse_numbers("--pixel", value, 2); });
      break;
    case 3:
      expect_contract("--accel", "--accel", 0, [&] { raystep::cli::parse_names("--accel", value); });
      break;
    case 4:
      expect_contract("--densities", "--densities", 0, [&] { raystep::cli::parse_densities(value); });
      break;
    case 5:
      // The message names the spec ("bad anti-aliasing 'x'"), as --aa and a scene's render.aa both use it.
      expect_contract("--aa", "anti-aliasing", 0, [&] { raystep::parse_antialiasing(value); });
      break;
    case 6: {
      raystep::BspDirections d;
      expect_contract("--bsp-directions", "", 0, [&] { raystep::parse_bsp_directions(value, &d); });
      break;
    }
    default:
      expect_contract("--heatmap", "", 0, [&] { raystep::parse_heat_quantity(value); });
  }
  return 0;
}
