/// \file exojoin.cpp
/// shellfrac_exojoin IN [OUT]: merges the per-rank results set IN.<np>.<rank> into one file OUT (default IN),
/// elements sorted by global id. Exit status 0 on success, 2 on usage or input error.
#include <exception>
#include <filesystem>
#include <iostream>
#include <string>

#include "shellfrac/io/results_reader.hpp"

int main(int argc, char** argv) {
  constexpr const char* usage =
      "usage: shellfrac_exojoin IN [OUT]\n"
      "  IN   base name of a per-rank results set IN.<np>.<rank> (as written by a run on np > 1 ranks)\n"
      "  OUT  joined file (default: IN)\n";
  if (argc >= 2 && (std::string(argv[1]) == "-h" || std::string(argv[1]) == "--help")) {
    std::cout << usage;
    return 0;
  }
  if (argc < 2 || argc > 3 || argv[1][0] == '-' || (argc == 3 && argv[2][0] == '-')) {
    std::cerr << "shellfrac_exojoin: expected IN [OUT]\n" << usage;
    return 2;
  }
  const std::string in = argv[1], out = argc == 3 ? argv[2] : argv[1];
  try {
    const auto files = shellfrac::io::find_rank_files(in);
    if (files.empty()) {
      std::error_code ec;
      std::cerr << "shellfrac_exojoin: no per-rank set " << in << ".<np>.<rank> found"
                << (std::filesystem::is_regular_file(in, ec) ? " (" + in + " is already a single file)" : "")
                << "\n";
      return 2;
    }
    for (const auto& f : files) {
      std::error_code ec;
      if (std::filesystem::equivalent(f, out, ec)) {
        std::cerr << "shellfrac_exojoin: error: the output " << out << " is one of the files to join (" << f
                  << "); name another output file\n";
        return 2;
      }
    }
    const auto results = shellfrac::io::read_results_files(files);
    shellfrac::io::write_results(results, out);
    std::cout << "shellfrac_exojoin: joined " << files.size() << " files (" << results.element_gids.size()
              << " elements, " << results.times.size() << " steps) into " << out << "\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "shellfrac_exojoin: error: " << e.what() << "\n";
    return 2;
  }
}
