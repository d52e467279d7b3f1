#pragma once
/// \file printable_text.hpp
/// Names and text values that go into result files, file names and messages must be printable UTF-8
/// (docs/hostile_input.md, "Input deck"): no control characters (C0, DEL, C1) and no bytes that are not
/// UTF-8, such as Latin-1 text.
#include <string>
#include <string_view>

#include "shellfrac/core/parameters.hpp"

namespace shellfrac::params {

/// What is wrong with `text` ("a control character (byte 0x01) at position 3", "a byte that is not UTF-8 (0xe9) at
/// position 6"; positions count bytes from 1), or "" if it is printable UTF-8.
std::string unprintable_part(std::string_view text);

/// `text` for a message: every byte that is not printable ASCII as \xNN.
std::string escaped(std::string_view text);

/// InputError naming ctx.file and the parameter path if the name of any entry of `pl` (sublists included), any
/// string value or any element of an Array(string) is not printable UTF-8.
void check_printable(const ParameterList& pl, const Context& ctx);

}  // namespace shellfrac::params
