# Warnings and sanitizers for every urbanpvs target, applied through one interface target so
# that third-party headers (CGAL, nlohmann) keep their own flags.
add_library(urbanpvs_warnings INTERFACE)
target_compile_options(urbanpvs_warnings INTERFACE
  $<$<CXX_COMPILER_ID:GNU,Clang>:-Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wcast-align
                                  -Woverloaded-virtual -Wimplicit-fallthrough>
  # GCC 12 reports -Wrestrict false positives inside std::string concatenation at -O2/-O3
  # (GCC bug 105329); the warning is off for GCC only.
  $<$<CXX_COMPILER_ID:GNU>:-Wno-restrict>
  $<$<AND:$<BOOL:${URBANPVS_WERROR}>,$<CXX_COMPILER_ID:GNU,Clang>>:-Werror>)

if(URBANPVS_SANITIZE)
  # vptr: CGAL's arrangement code (Boolean operations) trips UBSan's vptr check on its own
  # internal downcasts. GCC's -Wmaybe-uninitialized misfires on CGAL under sanitizers.
  add_compile_options(-fsanitize=address,undefined -fno-sanitize=vptr -fno-omit-frame-pointer
                      -fno-sanitize-recover=undefined
                      $<$<CXX_COMPILER_ID:GNU>:-Wno-maybe-uninitialized>)
  add_link_options(-fsanitize=address,undefined)
endif()
