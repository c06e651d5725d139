# Checked builds: NENRIN_SANITIZE adds AddressSanitizer and UndefinedBehaviorSanitizer (with
# float-cast-overflow, so a NaN or 1e308 cast to an int is caught) to every target; any report
# aborts the process, so a test that meets one fails. NENRIN_BUILD_FUZZ (clang only) instruments
# the code for libFuzzer and builds the fuzz targets in fuzz/. scripts/sanitize and scripts/fuzz
# configure build-sanitize/ with both.
option(NENRIN_SANITIZE "Build with AddressSanitizer + UndefinedBehaviorSanitizer" OFF)
option(NENRIN_BUILD_FUZZ "Build the libFuzzer targets in fuzz/ (needs clang)" OFF)

if(NENRIN_SANITIZE)
    set(nenrin_sanitizer_flags -fsanitize=address,undefined,float-cast-overflow
        -fno-sanitize-recover=all -fno-omit-frame-pointer)
    add_compile_options(${nenrin_sanitizer_flags})
    add_link_options(${nenrin_sanitizer_flags})
endif()

if(NENRIN_BUILD_FUZZ)
    if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
        message(FATAL_ERROR "NENRIN_BUILD_FUZZ needs clang (libFuzzer): configure with "
                            "-DCMAKE_CXX_COMPILER=clang++")
    endif()
    # Coverage feedback for libFuzzer in every library; the fuzz targets link the fuzzer itself.
    add_compile_options(-fsanitize=fuzzer-no-link)
endif()
