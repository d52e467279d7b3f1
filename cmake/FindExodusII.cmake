# Standalone Exodus II from Debian's libexodusii-dev: library libexoIIv2c, plus netCDF.
find_path(EXODUSII_INCLUDE_DIR exodusII.h)
find_library(EXODUSII_LIBRARY NAMES exoIIv2c exodus)
find_library(NETCDF_LIBRARY netcdf)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(ExodusII REQUIRED_VARS EXODUSII_LIBRARY NETCDF_LIBRARY EXODUSII_INCLUDE_DIR)
if(ExodusII_FOUND AND NOT TARGET ExodusII::ExodusII)
  add_library(ExodusII::ExodusII INTERFACE IMPORTED)
  set_target_properties(ExodusII::ExodusII PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${EXODUSII_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "${EXODUSII_LIBRARY};${NETCDF_LIBRARY}")
endif()
