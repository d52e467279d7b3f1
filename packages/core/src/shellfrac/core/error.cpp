#include "shellfrac/core/error.hpp"

namespace shellfrac::detail {

void throw_error(const char* file, int line, const std::string& msg) {
  std::ostringstream os;
  os << msg << " [" << file << ":" << line << "]";
  throw Error(os.str());
}

void throw_input_error(const std::string& msg) { throw InputError(msg); }

}  // namespace shellfrac::detail
