#pragma once
/// The C interface of the OpenVDB module (renderer/bake/vdb_writer), loaded by writeVdb on
/// first use so that OpenVDB and its compression libraries are loaded only by VDB bakes.

extern "C" {
typedef struct NenrinVdbGrid {
    int width, height, depth, channels;
    const float* data;  ///< channel-interleaved, x fastest, then y, then z
    const char* const* channelNames;
    double indexToWorld[16];          ///< row-major 4x4, row vectors (OpenVDB's convention)
    const char* const* metadataKeys;  ///< stored as "nenrin:KEY" on every grid
    const char* const* metadataValues;
    int metadataCount;
} NenrinVdbGrid;
/// Writes one float grid per channel to `path`; 0 on success, else a message in `error`.
typedef int (*NenrinVdbWriteFn)(const char* path, const NenrinVdbGrid* grid, char* error,
                                unsigned long errorSize);
}
