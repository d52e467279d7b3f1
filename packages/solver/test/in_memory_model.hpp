#pragma once
/// \file in_memory_model.hpp
/// Solver tests that build a model from a deck held in memory (deck_test_util.hpp), without files: the model as
/// a run builds it, and the input error a deck raises.
#include <string>

#include "shellfrac/core/error.hpp"
#include "shellfrac/solver/input/deck.hpp"
#include "shellfrac/solver/setup/model_setup.hpp"

namespace shellfrac::test {

/// The run model of `deck`; `file` is the deck's name in messages (and the base of relative paths). Collective.
inline solver::RunModel build_model(const Teuchos::RCP<Teuchos::ParameterList>& deck,
                                    const std::string& file = "in-memory deck") {
  return solver::build_run_model(solver::Deck::from_parameters(deck, file), MPI_COMM_WORLD);
}

/// The InputError message of building `deck`, or "" if it builds. Collective.
inline std::string input_error(const Teuchos::RCP<Teuchos::ParameterList>& deck, const std::string& file) {
  try {
    build_model(deck, file);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace shellfrac::test
