# One interface target carrying the warning flags; every amrvk target links it.
add_library(amrvk_warnings INTERFACE)
target_compile_options(amrvk_warnings INTERFACE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
                       -Wno-sign-conversion -Wnon-virtual-dtor
                       -Wno-missing-field-initializers)  # the Vulkan {sType} idiom
if(AMRVK_WERROR)
  target_compile_options(amrvk_warnings INTERFACE -Werror)
endif()
