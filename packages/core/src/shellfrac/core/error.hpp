#pragma once
/// \file error.hpp
/// Error handling. Two kinds of exception:
///  * shellfrac::InputError: the user's input (deck, mesh file, parameter) is wrong. The message is for the
///    user and names the file and the parameter; it is printed as is, without source locations.
///  * shellfrac::Error: an internal invariant or a library call failed; carries file:line.
/// SHELLFRAC_REQUIRE is always on; SHELLFRAC_ASSERT compiles out in Release (NDEBUG).
#include <sstream>
#include <stdexcept>
#include <string>

namespace shellfrac {

/// A failure that is the program's (or a library's) fault, not the user's.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A numerical failure of a run (non-finite state: an unstable time step or input). Thrown on every rank at
/// once, so that the run can write its last good state before stopping.
class NumericalError : public Error {
 public:
  using Error::Error;
};

/// Writing a result file failed (a full disk, a quota, a removed directory): the file is named. Thrown on every
/// rank at once; the program stops with its own exit code (6).
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A problem with the user's input: deck, mesh file, parameter value.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

namespace detail {
[[noreturn]] void throw_error(const char* file, int line, const std::string& msg);
[[noreturn]] void throw_input_error(const std::string& msg);
}  // namespace detail

}  // namespace shellfrac

/// Always-on check of a program invariant or library result; throws shellfrac::Error with file:line.
#define SHELLFRAC_REQUIRE(cond, msg)                                        \
  do {                                                                      \
    if (!(cond)) {                                                          \
      std::ostringstream shellfrac_os_;                                     \
      shellfrac_os_ << msg;                                                 \
      ::shellfrac::detail::throw_error(__FILE__, __LINE__, shellfrac_os_.str()); \
    }                                                                       \
  } while (0)

/// Always-on check of user input; throws shellfrac::InputError with the message only.
#define SHELLFRAC_INPUT_REQUIRE(cond, msg)                       \
  do {                                                           \
    if (!(cond)) {                                               \
      std::ostringstream shellfrac_os_;                          \
      shellfrac_os_ << msg;                                      \
      ::shellfrac::detail::throw_input_error(shellfrac_os_.str()); \
    }                                                            \
  } while (0)

#ifdef NDEBUG
#define SHELLFRAC_ASSERT(cond, msg) ((void)0)
#else
#define SHELLFRAC_ASSERT(cond, msg) SHELLFRAC_REQUIRE(cond, msg)
#endif
