#pragma once
/// \file parameters.hpp
/// Input decks are Teuchos XML parameter lists. Convention (docs/input_reference.xml): every configurable
/// component owns a `valid_parameters()` list (types, defaults, ranges, enumerations, docs with units),
/// validates its own sublist with `validate()` at depth 0 and converts it into a plain struct; kernels
/// never see a ParameterList. Errors are InputError messages naming the deck file, the parameter path
/// and the valid choices.
#include <mpi.h>

#include <Teuchos_ParameterList.hpp>
#include <Teuchos_RCP.hpp>
#include <functional>
#include <string>
#include <vector>

namespace shellfrac::params {

using Teuchos::ParameterList;
using Teuchos::RCP;

/// Where a sublist came from, for error messages: the deck file and the path of the sublist
/// inside it, e.g. {"plate.xml", "shellfrac->Mesh->Rectangle"}.
struct Context {
  std::string file;
  std::string path;
  /// The context of a child sublist.
  Context operator/(const std::string& child) const { return {file, path + "->" + child}; }
};

/// The array parameter `name` of `pl`, which must have exactly n entries, all finite: InputError naming the
/// file, the parameter path and the problem otherwise.
std::vector<double> fixed_array(const ParameterList& pl, const std::string& name, std::size_t n, const Context& ctx);

/// Reads an XML deck on rank 0 and broadcasts it to all ranks. A missing/unreadable file or malformed XML
/// is an InputError naming the file, thrown on every rank. Collective.
RCP<ParameterList> read_deck(const std::string& file, MPI_Comm comm = MPI_COMM_WORLD);

/// Validates `user` against `valid` at depth 0 and fills in defaults:
///  * every name in `user` must exist in `valid` (message lists the valid names and the closest match);
///  * types must match (an int given where a double is expected is accepted and converted);
///  * each value must pass the entry's validator (range, enumeration).
/// Sublists of `valid` are only checked for existence; their owners validate them.
/// Throws InputError naming ctx.file and ctx.path.
void validate(ParameterList& user, const ParameterList& valid, const Context& ctx);

/// After validate: InputError if `user` gives a parameter a value other than its default although the chosen kind
/// (`kind`, e.g. "a 'Clamped' boundary condition") does not use it (`applies(name)` false): a Velocity on a Clamped
/// condition, a Force on a Pressure load would be ignored without a word. A parameter left at its default (as in
/// the documented skeleton of --print-valid-parameters) is not an error.
void refuse_inapplicable(const ParameterList& user, const ParameterList& valid, const std::string& kind,
                         const std::function<bool(const std::string& name)>& applies, const Context& ctx);

/// A double parameter restricted to a range; `open_min`/`open_max` make the bound exclusive.
RCP<const Teuchos::ParameterEntryValidator> double_range(double min, double max, bool open_min = false,
                                                        bool open_max = false);
/// Double > 0.
RCP<const Teuchos::ParameterEntryValidator> positive_double();
/// Double >= 0.
RCP<const Teuchos::ParameterEntryValidator> non_negative_double();
/// An int parameter restricted to [min, max].
RCP<const Teuchos::ParameterEntryValidator> int_range(int min, int max);

/// Adds a string parameter restricted to `choices` (first-class enumeration, listed in errors and docs).
void set_choice(ParameterList& pl, const std::string& name, const std::string& default_value,
                const std::string& doc, const std::vector<std::string>& choices);

/// Writes `valid` as a documented XML deck skeleton: every parameter with its default value, type and a
/// comment with its documentation and valid values.
void write_documented_xml(std::ostream& os, const ParameterList& valid, int indent = 0);

/// Removes every validator from pl and its sublists (for echoing a validated deck as plain XML:
/// Teuchos cannot serialize shellfrac's own validators).
void strip_validators(ParameterList& pl);

/// Levenshtein distance, for "did you mean" suggestions.
std::size_t edit_distance(const std::string& a, const std::string& b);

}  // namespace shellfrac::params
