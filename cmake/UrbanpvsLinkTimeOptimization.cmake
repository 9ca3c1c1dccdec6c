# URBANPVS_LTO: link-time optimisation (CMake's IPO) for every target defined after this point,
# in Release builds, where the toolchain supports it. The bake's hot loop (FarField's sweep)
# calls SampleHorizon's queries in another file on every event; only LTO inlines them.
if(URBANPVS_LTO AND CMAKE_BUILD_TYPE STREQUAL "Release")
  include(CheckIPOSupported)
  check_ipo_supported(RESULT urbanpvs_ipo_supported OUTPUT urbanpvs_ipo_output LANGUAGES C CXX)
  # check_ipo_supported links without CMAKE_EXE_LINKER_FLAGS, and lld cannot read GCC's LTO
  # objects (it ignores GCC's linker plugin): every link would fail on missing symbols.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_EXE_LINKER_FLAGS MATCHES "-fuse-ld=lld")
    set(urbanpvs_ipo_supported NO)
    set(urbanpvs_ipo_output "GCC's LTO objects cannot be linked by lld (-fuse-ld=lld)")
  endif()
  if(urbanpvs_ipo_supported)
    set(CMAKE_INTERPROCEDURAL_OPTIMIZATION ON)
    # GCC 12 warns at the LTO link, where libosmium's builder is inlined into OsmReader.cpp,
    # that strlen reads past a 32-byte OSM object: libosmium keeps an object's strings in its
    # buffer right after it, which GCC does not see. A false positive in a library's header;
    # the same code compiles without it when not inlined across files.
    add_link_options($<$<CXX_COMPILER_ID:GNU>:-Wno-stringop-overread>)
    message(STATUS "urbanpvs: link-time optimisation on (URBANPVS_LTO)")
  else()
    message(STATUS "urbanpvs: link-time optimisation left off: ${urbanpvs_ipo_output}")
  endif()
endif()
