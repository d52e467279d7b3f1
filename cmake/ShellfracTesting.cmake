# Test helpers. Every test is a GTest executable linked with tests/unit_main.cpp
# (MPI + Kokkos initialised through Tpetra::ScopeGuard). MPI tests run the same binary at several rank
# counts: the rank count is a test parameter, not a separate test.
find_package(GTest REQUIRED)
# Debian's python3 has the packages the project installs (matplotlib, netCDF4); prefer it over any pyenv.
if(EXISTS /usr/bin/python3 AND NOT Python3_EXECUTABLE)
  set(Python3_EXECUTABLE /usr/bin/python3)
endif()
find_package(Python3 REQUIRED COMPONENTS Interpreter)
set(SHELLFRAC_MPIEXEC_PREFLAGS "--oversubscribe" CACHE STRING "Flags before the executable in mpiexec (np > 2 on 2 cores)")
add_library(shellfrac_test_main OBJECT ${PROJECT_SOURCE_DIR}/tests/unit_main.cpp)
target_link_libraries(shellfrac_test_main PUBLIC shellfrac::core GTest::gtest)

# shellfrac_add_test(name SOURCES a.cpp ... LIBS ... [NP 1 2 3] [LABELS ...])
# NP given: one ctest entry per rank count, named name.npN, run through mpiexec; else one serial entry.
function(shellfrac_add_test name)
  cmake_parse_arguments(arg "" "" "SOURCES;LIBS;NP;LABELS" ${ARGN})
  add_executable(${name} ${arg_SOURCES} $<TARGET_OBJECTS:shellfrac_test_main>)
  target_link_libraries(${name} PRIVATE ${arg_LIBS} shellfrac_test_main GTest::gtest)
  shellfrac_set_warnings(${name})
  target_compile_definitions(${name} PRIVATE SHELLFRAC_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
                                             SHELLFRAC_BINARY_DIR="${PROJECT_BINARY_DIR}")
  if(arg_NP)
    foreach(np IN LISTS arg_NP)
      add_test(NAME ${name}.np${np}
               COMMAND ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} ${np} ${SHELLFRAC_MPIEXEC_PREFLAGS}
                       $<TARGET_FILE:${name}>)
      set_tests_properties(${name}.np${np} PROPERTIES PROCESSORS ${np} LABELS "${arg_LABELS};mpi;np${np}"
                           WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
    endforeach()
  else()
    add_test(NAME ${name} COMMAND $<TARGET_FILE:${name}>)
    set_tests_properties(${name} PROPERTIES LABELS "${arg_LABELS};unit" WORKING_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR})
  endif()
endfunction()
