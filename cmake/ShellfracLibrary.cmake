# How shellfrac's libraries are made and installed.
include(GNUInstallDirs)

# shellfrac_set_warnings(target): warnings on for our own code (Trilinos headers are SYSTEM).
function(shellfrac_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wno-unused-parameter)
  # disc::Batch (a 32-byte vector) is passed between inline functions only, never across a library's interface:
  # GCC's note that such arguments changed ABI in GCC 4.6 (builds without AVX) does not concern it.
  target_compile_options(${target} PRIVATE -Wno-psabi)
  if(SHELLFRAC_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# shellfrac_install_package(pkg): the library shellfrac_<pkg> into the export set shellfracTargets (as
# shellfrac::<pkg>), its headers (packages/<pkg>/src/shellfrac/<pkg>/**.hpp) under include/.
function(shellfrac_install_package pkg)
  set_target_properties(shellfrac_${pkg} PROPERTIES EXPORT_NAME ${pkg})
  install(TARGETS shellfrac_${pkg} EXPORT shellfracTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/src/shellfrac DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
          FILES_MATCHING PATTERN "*.hpp")
endfunction()

# shellfrac_add_library(pkg SOURCES ... PUBLIC_DEPS ... PRIVATE_DEPS ...): library shellfrac_<pkg>, alias
# shellfrac::<pkg>, headers under packages/<pkg>/src/shellfrac/<pkg>/, installed and exported.
function(shellfrac_add_library pkg)
  cmake_parse_arguments(arg "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(shellfrac_${pkg} ${arg_SOURCES})
  add_library(shellfrac::${pkg} ALIAS shellfrac_${pkg})
  target_include_directories(shellfrac_${pkg} PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/src>
                                                     $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(shellfrac_${pkg} PUBLIC ${arg_PUBLIC_DEPS} PRIVATE ${arg_PRIVATE_DEPS})
  shellfrac_set_warnings(shellfrac_${pkg})
  shellfrac_install_package(${pkg})
endfunction()

# shellfrac_add_header_library(pkg DEPS ...): header-only INTERFACE library, installed and exported alike.
function(shellfrac_add_header_library pkg)
  cmake_parse_arguments(arg "" "" "DEPS" ${ARGN})
  add_library(shellfrac_${pkg} INTERFACE)
  add_library(shellfrac::${pkg} ALIAS shellfrac_${pkg})
  target_include_directories(shellfrac_${pkg} INTERFACE $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/src>
                                                        $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(shellfrac_${pkg} INTERFACE ${arg_DEPS})
  shellfrac_install_package(${pkg})
endfunction()
