# pddGmp.cmake — GMP and its C++ interface gmpxx as one INTERFACE target, pdd_gmpxx (exported as
# pdd::gmpxx). Debian's libgmp-dev ships neither a CMake config nor a find module; this finds
# the header and libraries and fails with a clear message when they are missing. Used by the
# build and, installed beside pddConfig.cmake, by consumers of the package.
if(NOT TARGET pdd_gmpxx AND NOT TARGET pdd::gmpxx)
  find_path(PDD_GMPXX_INCLUDE_DIR gmpxx.h)
  find_library(PDD_GMPXX_LIBRARY gmpxx)
  find_library(PDD_GMP_LIBRARY gmp)
  if(NOT PDD_GMPXX_INCLUDE_DIR OR NOT PDD_GMPXX_LIBRARY OR NOT PDD_GMP_LIBRARY)
    message(FATAL_ERROR "pdd needs GMP with its C++ interface (Debian: libgmp-dev)")
  endif()
endif()
if(NOT TARGET pdd_gmpxx AND NOT PDD_GMP_IMPORTED)
  if(PDD_GMP_FOR_CONSUMER)  # from pddConfig.cmake: the exported pdd::gmpxx names the libraries
    set(PDD_GMP_IMPORTED ON)
  else()
    add_library(pdd_gmpxx INTERFACE)
    target_include_directories(pdd_gmpxx INTERFACE $<BUILD_INTERFACE:${PDD_GMPXX_INCLUDE_DIR}>)
    # By name, so the exported target does not carry this machine's paths.
    target_link_libraries(pdd_gmpxx INTERFACE gmpxx gmp)
    set_target_properties(pdd_gmpxx PROPERTIES EXPORT_NAME gmpxx)
  endif()
endif()
