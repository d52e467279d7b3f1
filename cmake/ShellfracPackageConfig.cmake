# `cmake --install build --prefix P` installs shellfrac for other projects (README.md, "Using shellfrac from another project"):
#   P/bin                       shellfrac, shellfrac_meshtool, shellfrac_exocompare, shellfrac_exojoin
#   P/include/shellfrac/<pkg>   the headers of every package (and core/version.hpp, generated)
#   P/lib                       the libraries libshellfrac_<pkg>.a
#   P/lib/cmake/shellfrac       shellfrac-config.cmake (+ version file): find_package(shellfrac) gives the targets
#                               shellfrac::<pkg> (core disc materials mesh exodus meshio decomposition io solver)
include(CMakePackageConfigHelpers)
set(SHELLFRAC_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/shellfrac)

install(TARGETS shellfrac_trilinos EXPORT shellfracTargets)
install(TARGETS shellfrac shellfrac_meshtool shellfrac_exocompare shellfrac_exojoin
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(EXPORT shellfracTargets NAMESPACE shellfrac:: DESTINATION ${SHELLFRAC_CMAKE_DIR})

configure_package_config_file(cmake/shellfrac-config.cmake.in ${PROJECT_BINARY_DIR}/shellfrac-config.cmake
                              INSTALL_DESTINATION ${SHELLFRAC_CMAKE_DIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/shellfrac-config-version.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/shellfrac-config.cmake ${PROJECT_BINARY_DIR}/shellfrac-config-version.cmake
              cmake/ShellfracDependencies.cmake cmake/FindExodusII.cmake cmake/FindMETIS.cmake
        DESTINATION ${SHELLFRAC_CMAKE_DIR})
