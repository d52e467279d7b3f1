# shellfrac_set_warnings(target): warnings on for our own code (Trilinos headers are SYSTEM).
function(shellfrac_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wno-unused-parameter)
  if(SHELLFRAC_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# shellfrac_add_library(pkg SOURCES ... DEPS ...): library shellfrac_<pkg>, alias shellfrac::<pkg>,
# headers under packages/<pkg>/src/shellfrac/<pkg>/.
function(shellfrac_add_library pkg)
  cmake_parse_arguments(arg "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(shellfrac_${pkg} ${arg_SOURCES})
  add_library(shellfrac::${pkg} ALIAS shellfrac_${pkg})
  target_include_directories(shellfrac_${pkg} PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/src>)
  target_link_libraries(shellfrac_${pkg} PUBLIC ${arg_PUBLIC_DEPS} PRIVATE ${arg_PRIVATE_DEPS})
  shellfrac_set_warnings(shellfrac_${pkg})
endfunction()
