#pragma once
/// \file serial_compare.hpp
/// Rank-count independence check shared by the solver tests: the same deck run serially must give bitwise the
/// same history file and Exodus values (except the `rank` element field) as the run on np ranks.
#include <gtest/gtest.h>
#include <mpi.h>

#include <filesystem>
#include <string>

#include <Teuchos_ParameterList.hpp>
#include <Teuchos_XMLParameterListCoreHelpers.hpp>

#include "deck_test_util.hpp"
#include "shellfrac/io/results_reader.hpp"
#include "shellfrac/solver/simulation.hpp"

namespace shellfrac::test {

/// On rank 0 of a run on more than one rank: runs `deck` (whose Output Directory is `dir`) serially (MPI_COMM_SELF)
/// into dir/serial and expects its history and every Exodus nodal and element value except `rank` to equal those
/// of `par` bitwise, and the same fragment table and crack log if there are any. Collective (ends with a barrier).
inline void expect_same_as_serial(const solver::Simulation& par, const Teuchos::ParameterList& deck,
                                  const std::string& dir, const std::string& name) {
  if (parallel::size() > 1 && parallel::rank() == 0) {
    std::filesystem::create_directories(dir + "/serial");
    ASSERT_EQ(deck.sublist("Output").get<std::string>("Directory"), dir) << "the deck must write to " << dir;
    Teuchos::ParameterList serial = deck;
    serial.sublist("Output").set("Directory", dir + "/serial");
    Teuchos::writeParameterListToXmlFile(serial, dir + "/" + name + "_serial.xml");
    solver::Simulation ser(dir + "/" + name + "_serial.xml", MPI_COMM_SELF);
    ser.run();
    EXPECT_EQ(slurp(par.history_path()), slurp(ser.history_path())) << "history differs from the serial run";
    // Fracture runs: the same fragments and the same crack log (broken edges by global id, step and mode shares).
    for (const auto& [p, s] : {std::pair{par.fragments_path(), ser.fragments_path()},
                               std::pair{par.cracks_path(), ser.cracks_path()}}) {
      EXPECT_EQ(std::filesystem::exists(p), std::filesystem::exists(s)) << p;
      if (std::filesystem::exists(p)) {
        EXPECT_EQ(slurp(p), slurp(s)) << p << " differs from the serial run";
      }
    }
    const auto rp = io::read_results(par.exodus_path()), rs = io::read_results(ser.exodus_path());
    EXPECT_EQ(rp.times, rs.times);
    EXPECT_EQ(rp.nodal, rs.nodal);
    ASSERT_EQ(rp.element_names, rs.element_names);
    ASSERT_EQ(rp.element.size(), rs.element.size());
    for (std::size_t step = 0; step < rp.element.size(); ++step)
      for (std::size_t k = 0; k < rp.element_names.size(); ++k)
        if (rp.element_names[k] != "rank") {
          EXPECT_EQ(rp.element[step][k], rs.element[step][k]) << rp.element_names[k] << ", output " << step;
        }
  }
  MPI_Barrier(MPI_COMM_WORLD);
}

}  // namespace shellfrac::test
