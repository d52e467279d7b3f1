#pragma once
/// \file deck_structure.hpp
/// Checks of a deck's XML text made before Teuchos reads it (docs/hostile_input.md, "Input deck"): its size,
/// the nesting depth of its elements (Teuchos converts the element tree recursively, so thousands of nested
/// sublists overflow the stack) and entries given twice in one sublist (Teuchos keeps the last one silently).
/// Messages name the deck and the line.
#include <cstddef>
#include <string>
#include <string_view>

namespace shellfrac::params {

/// Largest input deck [bytes]: 16 MiB, far above any real deck (the examples are a few kB), so that a huge
/// file or a device such as /dev/zero is refused instead of read whole.
constexpr std::size_t max_deck_bytes = std::size_t{16} << 20;

/// Deepest element nesting of a deck: real decks need five levels or fewer.
constexpr int max_deck_nesting = 64;

/// The text of the deck `file`: InputError if it cannot be opened, is a directory, or has more than
/// max_deck_bytes (a regular file is measured before it is read; anything else, a pipe or a device, is read
/// only up to the limit).
std::string read_deck_text(const std::string& file);

/// InputError naming `file` and the line if the elements of `text` are nested more than max_deck_nesting deep,
/// or if two Parameter/ParameterList children of one ParameterList have the same name (both lines given).
/// Text that is not well-formed XML is left to the XML parser, which reports it.
void check_deck_structure(std::string_view text, const std::string& file);

}  // namespace shellfrac::params
