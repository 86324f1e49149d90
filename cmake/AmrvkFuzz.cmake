# AMRVK_FUZZ=ON: libFuzzer needs clang (Debian: clang-14 and libclang-rt-14-dev). Every object is
# compiled with -fsanitize=fuzzer-no-link,address,undefined (coverage for libFuzzer, ASan, UBSan
# that aborts on the first report, so libFuzzer keeps the input); the fuzz targets alone link
# -fsanitize=fuzzer (tests/fuzz/CMakeLists.txt).
if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  message(FATAL_ERROR "AMRVK_FUZZ=ON needs clang (configure with -DCMAKE_CXX_COMPILER=clang++ "
                      "-DCMAKE_C_COMPILER=clang; tools/run.sh fuzz does)")
endif()
set(AMRVK_FUZZ_FLAGS "-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer -g")
string(APPEND CMAKE_C_FLAGS " ${AMRVK_FUZZ_FLAGS}")
string(APPEND CMAKE_CXX_FLAGS " ${AMRVK_FUZZ_FLAGS}")
string(APPEND CMAKE_EXE_LINKER_FLAGS " -fsanitize=address,undefined")
set(AMRVK_BUILD_TESTS OFF CACHE BOOL "Build the GoogleTest suites" FORCE)
