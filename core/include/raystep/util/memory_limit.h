// The memory one input may take. A mesh or trace too large for the machine is refused before it is read, in
// one line naming the file, rather than read until the machine swaps or the kernel kills the debugger in
// front of a class. The estimate comes from the file's size alone, by factors measured on the 2-million-
// triangle mesh and the 10-million-event trace (bench/README.md, "Load"); a structure's from its primitives.
#pragma once

#include <cstdint>
#include <string>

namespace raystep {

// The machine's physical memory (sysconf), 0 when unknown.
uint64_t physical_memory_bytes();

// The most one input may need: RAYSTEP_MEMORY_LIMIT when set (bytes, or a whole number with a binary K, M, G
// or T: "512M"), else three quarters of the physical memory (the rest for the system, the display and the
// other programs). Throws InputError naming the variable for a malformed value.
uint64_t memory_limit_bytes();

// What the file holds, for the estimate of reading it.
enum class InputKind { obj_mesh, trace_json };

// Peak bytes that reading a file of file_bytes bytes needs (the text, the parser's data, the result), an
// upper estimate: kReadFactor[kind] bytes per byte of the file.
uint64_t read_memory_estimate(InputKind kind, uint64_t file_bytes);

// Throws InputError(path, 0, "too large to read: ...") when reading the file would need more than the limit.
void check_read_memory(const std::string& path, InputKind kind, uint64_t file_bytes);

// Peak bytes of a process that holds a scene of `primitives` primitives and builds the named structure over
// it (the scene, the structure and its builder's temporary arrays); 0 for an unknown name (brute force,
// bvol).
uint64_t build_memory_estimate(const std::string& structure, uint64_t primitives);

// Throws InputError(scene, 0, "too large for NAME: ...") when the build would need more than the limit.
void check_build_memory(const std::string& scene, const std::string& structure, uint64_t primitives);

// "1.5 GiB", "88 MiB", "12 KiB", "100 bytes".
std::string format_bytes(uint64_t bytes);

}  // namespace raystep
