# Fails if any C++ source differs from what clang-format makes of it.
file(GLOB_RECURSE sources
    ${SOURCE_DIR}/util/*.h ${SOURCE_DIR}/util/*.cpp
    ${SOURCE_DIR}/skeleton/*.h ${SOURCE_DIR}/skeleton/*.cpp
    ${SOURCE_DIR}/grain/*.h ${SOURCE_DIR}/grain/*.cpp
    ${SOURCE_DIR}/shader/*.h ${SOURCE_DIR}/shader/*.cpp
    ${SOURCE_DIR}/renderer/*.h ${SOURCE_DIR}/renderer/*.cpp
    ${SOURCE_DIR}/cli/*.h ${SOURCE_DIR}/cli/*.cpp
    ${SOURCE_DIR}/fit/*.h ${SOURCE_DIR}/fit/*.cpp
    ${SOURCE_DIR}/fuzz/*.h ${SOURCE_DIR}/fuzz/*.cpp
    ${SOURCE_DIR}/tests/*.cpp ${SOURCE_DIR}/bench/*.cpp)
set(bad "")
foreach(f ${sources})
    execute_process(COMMAND ${CLANG_FORMAT} --dry-run --Werror ${f}
        RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
    if(NOT rc EQUAL 0)
        list(APPEND bad ${f})
    endif()
endforeach()
if(bad)
    string(REPLACE ";" "\n  " list "${bad}")
    message(FATAL_ERROR "not clang-formatted (run scripts/format):\n  ${list}")
endif()
