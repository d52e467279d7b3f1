# Trilinos 13.2: Debian 12's (the default: Kokkos Serial only, no SEACAS) or one built by
# tools/build-trilinos.sh (Kokkos OpenMP + Serial, SEACAS), chosen with -DTrilinos_DIR=<prefix>/lib/cmake/Trilinos
# (tools/build.sh does it from SHELLFRAC_TRILINOS_PREFIX). Non-namespaced imported targets, no umbrella target:
# one INTERFACE wrapper carries includes and libraries for every shellfrac library.
find_package(MPI REQUIRED COMPONENTS C CXX)
find_package(Trilinos 13.2 REQUIRED COMPONENTS
  Kokkos KokkosCore TeuchosCore TeuchosParameterList TeuchosComm TpetraCore Zoltan2Core
  OPTIONAL_COMPONENTS SEACASExodus)
message(STATUS "Trilinos ${Trilinos_VERSION} from ${Trilinos_DIR}")

add_library(shellfrac_trilinos INTERFACE)
add_library(shellfrac::trilinos ALIAS shellfrac_trilinos)
target_include_directories(shellfrac_trilinos SYSTEM INTERFACE ${Trilinos_INCLUDE_DIRS} ${Trilinos_TPL_INCLUDE_DIRS})
target_link_libraries(shellfrac_trilinos INTERFACE ${Trilinos_LIBRARIES} ${Trilinos_TPL_LIBRARIES} MPI::MPI_CXX)
target_compile_features(shellfrac_trilinos INTERFACE cxx_std_17)

# Kokkos built with OpenMP: the plain imported targets do not carry the compiler's OpenMP flag.
set(SHELLFRAC_KOKKOS_OPENMP OFF)
if("OPENMP" IN_LIST Kokkos_DEVICES)
  find_package(OpenMP REQUIRED COMPONENTS CXX)
  target_link_libraries(shellfrac_trilinos INTERFACE OpenMP::OpenMP_CXX)
  set(SHELLFRAC_KOKKOS_OPENMP ON)
endif()
message(STATUS "Kokkos devices: ${Kokkos_DEVICES} (threads: ${SHELLFRAC_KOKKOS_OPENMP})")

# Exodus: SEACAS's from that Trilinos when it has it, else Debian's standalone libexoIIv2c (FindExodusII.cmake).
if(TARGET exodus)
  add_library(ExodusII::ExodusII INTERFACE IMPORTED)
  set_target_properties(ExodusII::ExodusII PROPERTIES INTERFACE_LINK_LIBRARIES exodus
                                                      INTERFACE_INCLUDE_DIRECTORIES "${Trilinos_INCLUDE_DIRS}")
  message(STATUS "Exodus: SEACAS (Trilinos)")
else()
  find_package(ExodusII REQUIRED)
  message(STATUS "Exodus: ${EXODUSII_LIBRARY}")
endif()
