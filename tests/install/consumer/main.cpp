// Reads a deck with an installed shellfrac and prints what it holds (tests/install/test_install.py).
#include <mpi.h>

#include <exception>
#include <stdexcept>
#include <iostream>

#include "shellfrac/core/version.hpp"
#include "shellfrac/solver/input/deck.hpp"

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int status = 0;
  try {
    if (argc != 2) throw std::runtime_error("usage: consumer DECK");
    const auto deck = shellfrac::solver::Deck::read(argv[1], MPI_COMM_WORLD);
    std::cout << "shellfrac " << shellfrac::version << ": " << deck.blocks.size() << " block(s), "
              << deck.materials.size() << " material(s), end time " << deck.time.end_time << "\n";
  } catch (const std::exception& e) {
    std::cerr << "consumer: " << e.what() << "\n";
    status = 1;
  }
  MPI_Finalize();
  return status;
}
