// The OpenVDB module: writes baked volumes as .vdb (renderer/bake/vdb_writer_abi.h). A shared
// module loaded on first use, so that OpenVDB is loaded only by processes that write VDB.

#include <openvdb/openvdb.h>

#include <cstring>
#include <stdexcept>
#include <string>

#include "renderer/bake/vdb_writer_abi.h"

extern "C" __attribute__((visibility("default"))) int nenrin_vdb_write(const char* path,
                                                                       const NenrinVdbGrid* grid,
                                                                       char* error,
                                                                       unsigned long errorSize) {
    try {
        openvdb::initialize();
        openvdb::math::Mat4d m;
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) m(r, c) = grid->indexToWorld[r * 4 + c];
        auto transform = openvdb::math::Transform::createLinearTransform(m);
        openvdb::GridPtrVec grids;
        const size_t channels = size_t(grid->channels);
        for (size_t c = 0; c < channels; ++c) {
            auto g = openvdb::FloatGrid::create(0.f);
            g->setName(grid->channelNames[c]);
            g->setTransform(transform->copy());
            g->setGridClass(openvdb::GRID_UNKNOWN);
            auto acc = g->getAccessor();
            size_t index = 0;
            for (int k = 0; k < grid->depth; ++k)
                for (int j = 0; j < grid->height; ++j)
                    for (int i = 0; i < grid->width; ++i, ++index)
                        acc.setValue(openvdb::Coord(i, j, k), grid->data[index * channels + c]);
            for (int k = 0; k < grid->metadataCount; ++k)
                g->insertMeta(std::string("nenrin:") + grid->metadataKeys[k],
                              openvdb::StringMetadata(grid->metadataValues[k]));
            grids.push_back(g);
        }
        openvdb::io::File file(path);
        file.write(grids);
        file.close();
        // OpenVDB does not report a failed write (a full disk leaves a short file and no
        // error): read the file back whole, which throws if any of it is missing.
        size_t stored = 0;
        try {
            openvdb::io::File check(path);
            check.open(false);
            stored = check.getGrids()->size();
            check.close();
        } catch (const std::exception&) {
        }
        if (stored != grids.size())
            throw std::runtime_error("the file written is incomplete (disk full?)");
        return 0;
    } catch (const std::exception& e) {
        if (errorSize > 0) {
            std::strncpy(error, e.what(), errorSize - 1);
            error[errorSize - 1] = '\0';
        }
        return 1;
    }
}
