# FindOsmium: libosmium is header-only; Debian ships no CMake config for it.
# Defines Osmium::Osmium with the libraries its XML/PBF/compressed readers need.
find_path(Osmium_INCLUDE_DIR osmium/version.hpp)
find_path(Protozero_INCLUDE_DIR protozero/version.hpp)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(Osmium REQUIRED_VARS Osmium_INCLUDE_DIR Protozero_INCLUDE_DIR)
if(Osmium_FOUND AND NOT TARGET Osmium::Osmium)
  include(CMakeFindDependencyMacro)
  find_dependency(Threads)
  find_dependency(EXPAT)
  find_dependency(BZip2)
  find_dependency(ZLIB)
  add_library(Osmium::Osmium INTERFACE IMPORTED)
  set_target_properties(Osmium::Osmium PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${Osmium_INCLUDE_DIR};${Protozero_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES "Threads::Threads;EXPAT::EXPAT;BZip2::BZip2;ZLIB::ZLIB")
endif()
mark_as_advanced(Osmium_INCLUDE_DIR Protozero_INCLUDE_DIR)
