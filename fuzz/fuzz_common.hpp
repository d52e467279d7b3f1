#pragma once
/// \file fuzz_common.hpp
/// Shared harness of the libFuzzer targets (fuzz/CMakeLists.txt, docs/hostile_input.md): the input bytes are
/// written to a file in a per-process scratch directory and the reader is called on that path.
/// Oracle: the reader returns normally, or throws shellfrac::InputError whose message names the file. Any other
/// exception, an InputError that does not name the file, a crash, a sanitizer report or a hang is a bug: the
/// harness prints what it saw and aborts, so libFuzzer saves the input as crash-<sha1>.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <typeinfo>

#include "shellfrac/core/error.hpp"

namespace shellfrac::fuzz {

/// A scratch directory unique to this process (under $TMPDIR or /tmp), created once and removed at exit.
/// The name is held by a never-destroyed object: the atexit handler runs after static destructors.
inline const std::string& scratch_dir() {
  static const std::string* const dir = [] {
    const char* tmp = std::getenv("TMPDIR");
    auto* d = new std::string(std::string(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") + "/shellfrac_fuzz_" +
                              std::to_string(static_cast<long>(getpid())));
    std::filesystem::create_directories(*d);
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(scratch_dir(), ec);
    });
    return d;
  }();
  return *dir;
}

/// Writes the fuzzer's bytes to scratch_dir()/name (replacing it); returns the path.
inline std::string write_input(const std::string& name, const std::uint8_t* data, std::size_t size) {
  const std::string path = scratch_dir() + "/" + name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  if (!out) {
    std::fprintf(stderr, "fuzz harness: cannot write %s\n", path.c_str());
    std::abort();
  }
  return path;
}

/// SHELLFRAC_FUZZ_VERBOSE=1 in the environment: print each InputError (to see what the inputs exercise).
inline bool verbose() {
  static const bool v = std::getenv("SHELLFRAC_FUZZ_VERBOSE") != nullptr;
  return v;
}

/// Runs read(path) under the oracle described in the file comment.
template <class Reader>
void run_reader(const std::string& path, Reader&& read) {
  try {
    read(path);
    if (verbose()) std::fprintf(stderr, "accepted\n");
  } catch (const InputError& e) {
    const std::string msg = e.what();
    if (verbose()) std::fprintf(stderr, "InputError: %s\n", msg.c_str());
    if (msg.find(path) == std::string::npos) {
      std::fprintf(stderr, "fuzz harness: InputError that does not name the file %s:\n  %s\n", path.c_str(),
                   msg.c_str());
      std::abort();
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz harness: %s is not an InputError:\n  %s\n", typeid(e).name(), e.what());
    std::abort();
  } catch (...) {
    std::fprintf(stderr, "fuzz harness: an exception that is not a std::exception\n");
    std::abort();
  }
}

}  // namespace shellfrac::fuzz
