# The memory allocator of phdslam's programs (the `phdslam` command line and the benchmarks).
#
# A filter step makes a few dozen short-lived allocations per particle; with glibc's malloc a
# PHD-SLAM 3.0 step takes about 6 % longer (filter_step_benchmark, validation/REPRODUCTION.md).
# TCMalloc (Debian's libtcmalloc-minimal4) serves them from per-thread caches. The allocator
# changes no result, only time: every number is computed by the same instructions on the same
# values.
#
#   -DPHDSLAM_MALLOC=tcmalloc   (default) link libtcmalloc_minimal; a configure error when missing
#   -DPHDSLAM_MALLOC=system     glibc's malloc
#
# Sanitizer and fuzzing builds always use the system allocator (ASan replaces malloc).
set(PHDSLAM_MALLOC "tcmalloc" CACHE STRING "Allocator of the programs: tcmalloc or system")
set_property(CACHE PHDSLAM_MALLOC PROPERTY STRINGS tcmalloc system)
if(NOT PHDSLAM_MALLOC MATCHES "^(tcmalloc|system)$")
  message(FATAL_ERROR "PHDSLAM_MALLOC is '${PHDSLAM_MALLOC}'; expected tcmalloc or system")
endif()

# phdslam_use_malloc(TARGET...): links the chosen allocator into the given programs.
set(PHDSLAM_MALLOC_LINK "")
if(PHDSLAM_MALLOC STREQUAL "tcmalloc" AND NOT PHDSLAM_SANITIZE AND NOT PHDSLAM_FUZZ)
  # The versioned name needs only the runtime package, not the -dev one.
  find_library(PHDSLAM_TCMALLOC_LIBRARY NAMES tcmalloc_minimal libtcmalloc_minimal.so.4)
  if(NOT PHDSLAM_TCMALLOC_LIBRARY)
    message(FATAL_ERROR "PHDSLAM_MALLOC=tcmalloc but libtcmalloc_minimal was not found: install "
                        "libtcmalloc-minimal4 (ci/install-deps.sh does) or configure with "
                        "-DPHDSLAM_MALLOC=system")
  endif()
  # Kept even where the linker drops libraries no symbol needs: malloc comes through libstdc++.
  set(PHDSLAM_MALLOC_LINK "-Wl,--push-state,--no-as-needed" "${PHDSLAM_TCMALLOC_LIBRARY}"
                         "-Wl,--pop-state")
  message(STATUS "phdslam: programs link ${PHDSLAM_TCMALLOC_LIBRARY}")
else()
  message(STATUS "phdslam: programs use the system allocator")
endif()

function(phdslam_use_malloc)
  foreach(target IN LISTS ARGN)
    target_link_libraries(${target} PRIVATE ${PHDSLAM_MALLOC_LINK})
  endforeach()
endfunction()
