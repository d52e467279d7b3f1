# Trilinos 13.2 and the other dependencies (ShellfracDependencies.cmake), and one INTERFACE target,
# shellfrac::trilinos, that carries Trilinos's includes and libraries for every shellfrac library (Trilinos 13.2
# has non-namespaced imported targets and no umbrella target). It is exported with the libraries.
include(ShellfracDependencies)
message(STATUS "Trilinos ${Trilinos_VERSION} from ${Trilinos_DIR}")

add_library(shellfrac_trilinos INTERFACE)
add_library(shellfrac::trilinos ALIAS shellfrac_trilinos)
set_target_properties(shellfrac_trilinos PROPERTIES EXPORT_NAME trilinos)
target_include_directories(shellfrac_trilinos SYSTEM INTERFACE ${Trilinos_INCLUDE_DIRS} ${Trilinos_TPL_INCLUDE_DIRS})
target_link_libraries(shellfrac_trilinos INTERFACE ${Trilinos_LIBRARIES} ${Trilinos_TPL_LIBRARIES} MPI::MPI_CXX)
target_compile_features(shellfrac_trilinos INTERFACE cxx_std_17)
if(SHELLFRAC_KOKKOS_OPENMP)
  target_link_libraries(shellfrac_trilinos INTERFACE OpenMP::OpenMP_CXX)
endif()
message(STATUS "Kokkos devices: ${Kokkos_DEVICES} (threads: ${SHELLFRAC_KOKKOS_OPENMP})")
message(STATUS "Exodus: ${SHELLFRAC_EXODUS_FROM}")
