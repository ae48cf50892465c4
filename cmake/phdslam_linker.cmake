# The linker of this build's own programs and tests: lld (Debian's lld) when the compiler accepts
# -fuse-ld=lld, else the compiler's default (GNU ld). A release build links about 90 programs,
# each against Ceres, MRPT and their dependencies; lld links each several times quicker. The
# linker changes no result: it places the same compiled instructions, nothing is recompiled.
#
#   -DPHDSLAM_USE_LLD=ON    (default) lld when available
#   -DPHDSLAM_USE_LLD=OFF   the compiler's default linker
#
# Set for this directory tree only (add_link_options), so the installed package passes nothing on
# to the projects that use it.
option(PHDSLAM_USE_LLD "Link the project's programs with lld when the compiler can" ON)
if(PHDSLAM_USE_LLD)
  include(CheckLinkerFlag)
  check_linker_flag(CXX -fuse-ld=lld PHDSLAM_HAVE_LLD)
  if(PHDSLAM_HAVE_LLD)
    add_link_options(-fuse-ld=lld)
  else()
    message(STATUS "phdslam: lld not found, linking with the default linker (apt-get install lld)")
  endif()
endif()
