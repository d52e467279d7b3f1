# The libraries shellfrac builds on, found the same way by shellfrac's own build and by a project that uses an
# installed shellfrac (shellfrac-config.cmake includes this file): MPI, Trilinos 13.2 (Debian's, or one built by
# tools/build-trilinos.sh, chosen with -DTrilinos_DIR=<prefix>/lib/cmake/Trilinos), OpenMP when that Trilinos's
# Kokkos has it, Exodus II (SEACAS's from that Trilinos, else Debian's libexoIIv2c: FindExodusII.cmake), METIS
# (FindMETIS.cmake). Defines ExodusII::ExodusII and METIS::METIS, and SHELLFRAC_KOKKOS_OPENMP.
find_package(MPI REQUIRED COMPONENTS C CXX)
find_package(Trilinos 13.2 REQUIRED COMPONENTS
  Kokkos KokkosCore TeuchosCore TeuchosParameterList TeuchosComm TpetraCore Zoltan2Core
  OPTIONAL_COMPONENTS SEACASExodus)

# Kokkos built with OpenMP: the plain imported targets do not carry the compiler's OpenMP flag.
set(SHELLFRAC_KOKKOS_OPENMP OFF)
if("OPENMP" IN_LIST Kokkos_DEVICES)
  find_package(OpenMP REQUIRED COMPONENTS CXX)
  set(SHELLFRAC_KOKKOS_OPENMP ON)
endif()

if(TARGET exodus)
  if(NOT TARGET ExodusII::ExodusII)
    add_library(ExodusII::ExodusII INTERFACE IMPORTED)
    set_target_properties(ExodusII::ExodusII PROPERTIES INTERFACE_LINK_LIBRARIES exodus
                                                        INTERFACE_INCLUDE_DIRECTORIES "${Trilinos_INCLUDE_DIRS}")
  endif()
  set(SHELLFRAC_EXODUS_FROM "SEACAS (Trilinos)")
else()
  find_package(ExodusII REQUIRED)
  set(SHELLFRAC_EXODUS_FROM "${EXODUSII_LIBRARY}")
endif()
find_package(METIS REQUIRED)
