#pragma once
/// \file memory_release.hpp
/// How the executables ask the C library to give freed memory back to the system.

namespace shellfrac {

/// Block size from which the C library maps each allocation on its own, so that freeing it returns it to the
/// system: 1 MiB [bytes].
inline constexpr int own_mapping_bytes = 1 << 20;

/// Makes blocks of own_mapping_bytes and more go back to the system when freed. glibc's malloc otherwise raises that
/// threshold to the size of each large block freed, up to 32 MiB, and serves later blocks below it from the heap,
/// where memory freed in the middle stays resident: after the set-up's exchanges every rank kept up to 40 MiB it
/// no longer used, more than its share of the mesh at 500 000 elements on 4 ranks (docs/performance.md,
/// "Distributed set-up"). Call once, first thing in main, before any large allocation. No effect elsewhere than
/// glibc.
void release_freed_memory_promptly();

}  // namespace shellfrac
