/// \file fuzz_gmsh.cpp
/// libFuzzer target: the Gmsh .msh reader, meshio::read_gmsh (formats 2.2 / 4.1, ASCII / binary), which also
/// runs mesh::check_mesh on the result. Seeds: tests/fuzz_corpus/gmsh/ (also tests/data/gmsh/*.msh).
/// Build and run (docs/hostile_input.md):
///   cmake --build build-fuzz --target fuzz_gmsh
///   build-fuzz/fuzz/fuzz_gmsh -max_total_time=600 -rss_limit_mb=4096 /tmp/corpus_gmsh tests/fuzz_corpus/gmsh
/// Expected outcome of every input: a mesh, or a shellfrac::InputError naming the file (fuzz_common.hpp).
#include <cstddef>
#include <cstdint>

#include "fuzz_common.hpp"
#include "shellfrac/meshio/gmsh_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = shellfrac::fuzz::write_input("input.msh", data, size);
  shellfrac::fuzz::run_reader(path, [](const std::string& p) { shellfrac::meshio::read_gmsh(p); });
  return 0;
}
