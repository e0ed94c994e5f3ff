// Build options of every acceleration structure, as the command line and the debugger's structure panel set
// them, and the factory that takes them.
#pragma once

#include <memory>
#include <string>

#include "raystep/accel/accelerator.h"
#include "raystep/accel/grid.h"

namespace raystep {

struct StructureOptions {
  GridOptions grid;
};

// Throws InputError("", 0, "unknown accelerator ...") for an unknown name.
std::unique_ptr<Accelerator> make_accelerator(const std::string& name, const StructureOptions& options);

}  // namespace raystep
