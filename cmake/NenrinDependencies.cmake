# Finds the Debian 12 packages nenrin builds on (see scripts/install-deps) and papers over
# their packaging quirks, so the library CMakeLists only name imported targets.
find_package(TBB CONFIG REQUIRED COMPONENTS tbb)
find_package(embree 3 CONFIG REQUIRED)
find_package(OpenEXR CONFIG REQUIRED)
find_package(OpenImageIO CONFIG REQUIRED)
find_package(PNG REQUIRED)
find_package(nlohmann_json CONFIG REQUIRED)
find_package(simdjson CONFIG REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
find_package(fmt CONFIG REQUIRED)
find_package(tinyobjloader CONFIG REQUIRED)
find_package(TinyGLTF CONFIG REQUIRED)
# The fit from photographs (fit/): least squares.
find_package(Ceres CONFIG REQUIRED)

# Quirk: OpenColorIO's CMake config computes an empty prefix on Debian; pkg-config works.
find_package(PkgConfig REQUIRED)
pkg_check_modules(OCIO REQUIRED IMPORTED_TARGET OpenColorIO)
pkg_check_modules(XXHASH REQUIRED IMPORTED_TARGET libxxhash)
pkg_check_modules(LIBDEFLATE REQUIRED IMPORTED_TARGET libdeflate)

# Quirk: Debian's OpenImageIO target lists /usr/include/opencv4, which does not exist.
foreach(prop INTERFACE_INCLUDE_DIRECTORIES INTERFACE_SYSTEM_INCLUDE_DIRECTORIES)
    get_target_property(dirs OpenImageIO::OpenImageIO ${prop})
    if(dirs)
        list(FILTER dirs EXCLUDE REGEX "opencv4")
        set_target_properties(OpenImageIO::OpenImageIO PROPERTIES ${prop} "${dirs}")
    endif()
endforeach()

if(NENRIN_BUILD_TESTS)
    find_package(GTest CONFIG REQUIRED)
endif()
if(NENRIN_BUILD_BENCH)
    find_package(benchmark CONFIG REQUIRED)
endif()

# Quirk: OpenVDB ships only a FindOpenVDB.cmake beside stale FindTBB/FindOpenEXR modules:
# append its folder last, after everything else was found.
list(APPEND CMAKE_MODULE_PATH /usr/lib/x86_64-linux-gnu/cmake/OpenVDB /usr/lib/cmake/OpenVDB)
find_package(OpenVDB REQUIRED)
find_package(Threads REQUIRED)
