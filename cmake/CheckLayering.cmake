cmake_minimum_required(VERSION 3.20)
# Fails if a library's source includes a header of a library above it or beside it: the
# dependency order of README.md's layout table, written out here as what each library may
# include (besides its own headers). tests/, bench/ and fuzz/ may include anything.
set(sources_of_library
    "util:"
    "skeleton:util"
    "skeleton/sources/hayashi:skeleton,util"
    "skeleton/sources/akagi:skeleton,util"
    "skeleton/sources/kanayama:skeleton,util"
    "skeleton/sources/kunii:skeleton,util"
    "skeleton/sources/measured:skeleton,util"
    "grain:skeleton,util"
    "shader:grain,skeleton,util"
    "renderer/geometry:util"
    "renderer/products:geometry,grain,skeleton,util"
    "renderer/furniture:renderer/products,renderer/geometry,grain,skeleton,util"
    "renderer:renderer/products,renderer/geometry,shader,grain,skeleton,util"
    "renderer/bake:renderer,renderer/products,renderer/geometry,shader,grain,skeleton,util"
    "renderer/texture_set:renderer,renderer/products,renderer/geometry,shader,grain,skeleton,util"
    "renderer/pov:renderer/bake,renderer,renderer/products,renderer/geometry,shader,grain,skeleton,util"
    "renderer/preview:renderer,renderer/products,renderer/geometry,shader,grain,skeleton,util"
    "renderer/farm:renderer/bake,renderer,renderer/products,renderer/geometry,shader,grain,skeleton,util"
    "renderer/jobs:renderer/denoise,renderer/farm,renderer/bake,renderer/furniture,renderer/texture_set,renderer,renderer/products,renderer/geometry,shader,grain,skeleton,util"
    "renderer/stats:renderer,renderer/products,renderer/geometry,shader,grain,skeleton,util"
    "renderer/image_error:"
    "renderer/denoise:renderer,renderer/products,renderer/geometry,shader,grain,skeleton,util"
    "fit:renderer/bake,renderer/stats,renderer,renderer/products,renderer/geometry,shader,grain,skeleton,util"
    "cli:*")

set(libraries "")
foreach(entry ${sources_of_library})
    string(REPLACE ":" ";" parts "${entry}")
    list(GET parts 0 lib)
    list(APPEND libraries ${lib})
    list(LENGTH parts n)
    if(n GREATER 1)
        list(GET parts 1 allowed)
        string(REPLACE "," ";" allowed "${allowed}")
    else()
        set(allowed "")
    endif()
    # "geometry" above is short for renderer/geometry.
    list(TRANSFORM allowed REPLACE "^geometry$" "renderer/geometry")
    set(allowed_${lib} ${allowed})
endforeach()

# The library a path belongs to: the longest library folder that contains it.
function(library_of path out)
    set(best "")
    foreach(lib ${libraries})
        string(LENGTH "${lib}/" n)
        string(SUBSTRING "${path}" 0 ${n} head)
        string(LENGTH "${best}" best_n)
        if(head STREQUAL "${lib}/" AND n GREATER best_n)
            set(best ${lib})
        endif()
    endforeach()
    set(${out} "${best}" PARENT_SCOPE)
endfunction()

file(GLOB_RECURSE files RELATIVE ${SOURCE_DIR}
    ${SOURCE_DIR}/util/*.h ${SOURCE_DIR}/util/*.cpp
    ${SOURCE_DIR}/skeleton/*.h ${SOURCE_DIR}/skeleton/*.cpp
    ${SOURCE_DIR}/grain/*.h ${SOURCE_DIR}/grain/*.cpp
    ${SOURCE_DIR}/shader/*.h ${SOURCE_DIR}/shader/*.cpp
    ${SOURCE_DIR}/renderer/*.h ${SOURCE_DIR}/renderer/*.cpp
    ${SOURCE_DIR}/cli/*.h ${SOURCE_DIR}/cli/*.cpp)
set(bad "")
set(checked 0)
foreach(f ${files})
    library_of("${f}" lib)
    if(lib STREQUAL "" OR allowed_${lib} STREQUAL "*")
        continue()
    endif()
    file(STRINGS ${SOURCE_DIR}/${f} includes REGEX "^#include \"[^\"]+\"")
    foreach(line ${includes})
        string(REGEX REPLACE "^#include \"([^\"]+)\".*" "\\1" header "${line}")
        library_of("${header}" target)
        math(EXPR checked "${checked} + 1")
        if(target STREQUAL "" OR target STREQUAL lib)
            continue()  # a system-style or generated header, or the library's own
        endif()
        list(FIND allowed_${lib} ${target} found)
        if(found EQUAL -1)
            list(APPEND bad "${f} (${lib}) includes ${header} (${target})")
        endif()
    endforeach()
endforeach()
if(checked EQUAL 0)
    message(FATAL_ERROR "layering check: no includes found under ${SOURCE_DIR}")
endif()
if(bad)
    string(REPLACE ";" "\n  " list "${bad}")
    message(FATAL_ERROR "includes that run against the library order:\n  ${list}")
endif()
message(STATUS "layering check: ${checked} includes follow the library order")
