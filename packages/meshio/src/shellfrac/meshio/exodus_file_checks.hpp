#pragma once
/// \file exodus_file_checks.hpp
/// Checks of an Exodus file's netCDF structure made before the netCDF and Exodus libraries read it: both trust
/// sizes declared in the file (docs/hostile_input.md). Used by the Exodus mesh reader.
#include <cstdint>
#include <string>

namespace shellfrac::meshio {

/// Checks the header of a netCDF classic file (CDF-1, CDF-2 or CDF-5; "NetCDF Classic Format Specification")
/// before the netCDF library parses it: every count must fit in the file, every type and dimension id must be
/// valid. libnetcdf allocates what a header declares before checking it against the file: a 2.6 kB file
/// declaring a variable with 822083584 dimensions made it allocate and touch 6.5 GB. Then the data of every
/// fixed-size variable must lie inside the file (the library writes files to their full size; reading past
/// the end of a truncated file gives zeros, hence misleading messages). Returns false when the file is not a
/// netCDF classic file (netCDF-4 / HDF5 files are left to the library).
bool check_netcdf_classic_header(const std::string& path, std::uintmax_t size);

/// Checks the parts of the file's netCDF structure that libexodusII (6.02) trusts when it reads into buffers
/// sized from other parts, before any Exodus call. Each of these was a buffer overflow in the library (heap or
/// stack; crashes or silent memory corruption), found with fuzz_exodus, valgrind and ASan
/// (docs/hostile_input.md):
///  * variables it reads whole (nc_get_var) into buffers sized by the Exodus dimensions: coordinates,
///    connectivity, id and status arrays, set entries; each must have exactly the size of its dimensions;
///  * global attributes it reads into a single number (version, word size, ...): exactly one value;
///  * the element type attribute of a block, read into a 33-character buffer: at most 32 characters.
/// Files that netCDF cannot open are left to ex_open (which reports them).
void check_exodus_structure(const std::string& path);

}  // namespace shellfrac::meshio
