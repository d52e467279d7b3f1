/// \file fuzz_exodus.cpp
/// libFuzzer target: the Exodus II mesh reader, meshio::read_exodus_mesh (through libexodusII / netCDF), which
/// also runs mesh::check_mesh on the result. Seeds: tests/fuzz_corpus/exodus/ (tiny meshes written by
/// `shellfrac_meshtool convert` from tests/data/gmsh; netCDF classic / 64-bit offset files).
/// Build and run (docs/hostile_input.md):
///   cmake --build build-fuzz --target fuzz_exodus
///   build-fuzz/fuzz/fuzz_exodus -max_total_time=600 -rss_limit_mb=4096 /tmp/corpus_exodus tests/fuzz_corpus/exodus
/// Expected outcome of every input: a mesh, or a shellfrac::InputError naming the file (fuzz_common.hpp).
/// Bugs of the uninstrumented netCDF / HDF5 libraries can only show up as crashes (SEGV) here.
#include <cstddef>
#include <cstdint>

#include "fuzz_common.hpp"
#include "shellfrac/meshio/exodus_mesh_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = shellfrac::fuzz::write_input("input.exo", data, size);
  shellfrac::fuzz::run_reader(path, [](const std::string& p) { shellfrac::meshio::read_exodus_mesh(p); });
  return 0;
}
