# The suite's test kernel_sources (tests/CMakeLists.txt): core/CMakeLists.txt's
# MPMSTAB_KERNEL_SOURCES must be exactly the sources of core/ whose code depends on the
# instruction-set switch of core/base/simd.hpp, since the reproducibility test compiles only
# those per instruction set (kernels_portable, kernels_avx2) and links the rest compiled once.
#
# A file uses the switch when it names one of the macros simd.hpp sets per version
# (MPMSTAB_SIMD_CLONES, MPMSTAB_AVX512*, MPMSTAB_AVX2*) or the switch itself (MPMSTAB_KERNELS_*);
# a source depends on it when it or a header it includes (quoted includes, resolved in core/,
# followed transitively) uses it. simd.hpp itself, which only defines them, does not count, nor
# do MPMSTAB_INLINE and MPMSTAB_IVDEP, which are the same in every version.
#
# Usage: cmake -DCORE=<core folder> "-DKERNEL_SOURCES=<absolute paths>" -P kernel_sources.cmake
cmake_minimum_required(VERSION 3.22)
if(NOT CORE OR NOT KERNEL_SOURCES)
  message(FATAL_ERROR "kernel_sources.cmake: CORE and KERNEL_SOURCES must be given")
endif()

set(switch_regex "MPMSTAB_(SIMD_CLONES|AVX512|AVX2|KERNELS_)")

# Whether `file` or anything it includes from core/ uses the switch (memoized in a global
# property per file; `visiting` breaks include cycles).
function(uses_switch file out)
  get_property(known GLOBAL PROPERTY "uses:${file}" SET)
  if(known)
    get_property(value GLOBAL PROPERTY "uses:${file}")
    set(${out} ${value} PARENT_SCOPE)
    return()
  endif()
  set_property(GLOBAL PROPERTY "uses:${file}" FALSE)  # while visiting
  set(value FALSE)
  if(NOT file STREQUAL "${CORE}/base/simd.hpp")
    file(STRINGS "${file}" lines REGEX "${switch_regex}")
    foreach(line IN LISTS lines)
      string(REGEX REPLACE "//.*$" "" code "${line}")  # a comment naming a macro is no use
      if(code MATCHES "${switch_regex}")
        set(value TRUE)
      endif()
    endforeach()
  endif()
  file(STRINGS "${file}" includes REGEX "^[ \t]*#[ \t]*include[ \t]*\"")
  foreach(line IN LISTS includes)
    string(REGEX REPLACE "^[^\"]*\"([^\"]+)\".*$" "\\1" target "${line}")
    if(EXISTS "${CORE}/${target}")
      uses_switch("${CORE}/${target}" sub)
      if(sub)
        set(value TRUE)
      endif()
    endif()
  endforeach()
  set_property(GLOBAL PROPERTY "uses:${file}" ${value})
  set(${out} ${value} PARENT_SCOPE)
endfunction()

file(GLOB_RECURSE sources "${CORE}/*.cpp")
set(expected "")
foreach(source IN LISTS sources)
  uses_switch("${source}" uses)
  if(uses)
    list(APPEND expected "${source}")
  endif()
endforeach()

set(listed "")
foreach(source IN LISTS KERNEL_SOURCES)
  get_filename_component(source "${source}" ABSOLUTE)
  list(APPEND listed "${source}")
endforeach()

set(wrong "")
foreach(source IN LISTS expected)
  if(NOT source IN_LIST listed)
    file(RELATIVE_PATH rel "${CORE}" "${source}")
    string(APPEND wrong "\n  ${rel} uses the switch: move it to MPMSTAB_KERNEL_SOURCES")
  endif()
endforeach()
foreach(source IN LISTS listed)
  if(NOT source IN_LIST expected)
    file(RELATIVE_PATH rel "${CORE}" "${source}")
    string(APPEND wrong "\n  ${rel} does not use the switch: move it to mpmstab_core_common")
  endif()
endforeach()
if(wrong)
  message(FATAL_ERROR "core/CMakeLists.txt's kernel sources are wrong:${wrong}")
endif()
list(LENGTH expected n)
message(STATUS "kernel_sources: the ${n} sources that use the switch are MPMSTAB_KERNEL_SOURCES")
