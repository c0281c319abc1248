# Compile options shared by every masnet target, linked PRIVATE so they never leak to users.
add_library(masnet_options INTERFACE)
add_library(masnet::options ALIAS masnet_options)
target_compile_options(masnet_options INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion
  # Determinism: no fused multiply-add contraction, never -ffast-math.
  -ffp-contract=off)
if(MASNET_ASSERTIONS)
  target_compile_definitions(masnet_options INTERFACE MASNET_ASSERTIONS=1)
endif()
