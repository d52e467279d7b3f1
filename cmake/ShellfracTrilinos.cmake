# Debian 12 ships Trilinos 13.2: non-namespaced imported targets, no umbrella target.
# One INTERFACE wrapper carries includes and libraries for every shellfrac library.
find_package(MPI REQUIRED COMPONENTS C CXX)
find_package(Trilinos 13.2 REQUIRED COMPONENTS
  Kokkos KokkosCore TeuchosCore TeuchosParameterList TeuchosComm TpetraCore Zoltan2Core)
message(STATUS "Trilinos ${Trilinos_VERSION} from ${Trilinos_DIR}")

add_library(shellfrac_trilinos INTERFACE)
add_library(shellfrac::trilinos ALIAS shellfrac_trilinos)
target_include_directories(shellfrac_trilinos SYSTEM INTERFACE ${Trilinos_INCLUDE_DIRS} ${Trilinos_TPL_INCLUDE_DIRS})
target_link_libraries(shellfrac_trilinos INTERFACE ${Trilinos_LIBRARIES} ${Trilinos_TPL_LIBRARIES} MPI::MPI_CXX)
target_compile_features(shellfrac_trilinos INTERFACE cxx_std_17)
