#include "renderer/bake/grid_writers.h"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>
#include <openvdb/openvdb.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>

#include "renderer/exr_file.h"
#include "util/atomic_output.h"
#include "util/input_error.h"

namespace nenrin {

namespace fs = std::filesystem;

std::vector<std::string> writeExr(const BakedGrid& grid, const std::string& path) {
    checkOutputName(path, {".exr"});
    AtomicOutput out(path);
    std::map<std::string, std::string> metadata = grid.metadata;
    if (grid.depth > 1) {
        metadata["volume_resolution"] =
            fmt::format("{} {} {}", grid.width, grid.height, grid.depth);
        metadata["volume_layout"] =
            "atlas: z slice k occupies rows k*Sy .. k*Sy+Sy-1, y index = row - k*Sy";
    }
    writeFloatExr(path, out.temporaryPath(), grid.width, grid.height * grid.depth,
                  {kBakeChannels.begin(), kBakeChannels.end()}, grid.data.data(), metadata);
    out.commit();
    return {path};
}

std::vector<std::string> writeVdb(const BakedGrid& grid, const std::string& path) {
    openvdb::initialize();
    AtomicOutput out(path);
    openvdb::GridPtrVec grids;
    openvdb::math::Mat4d m = openvdb::math::Mat4d::identity();
    m.setRow(0, openvdb::math::Vec4d(grid.stepX.x, grid.stepX.y, grid.stepX.z, 0));
    m.setRow(1, openvdb::math::Vec4d(grid.stepY.x, grid.stepY.y, grid.stepY.z, 0));
    m.setRow(2, openvdb::math::Vec4d(grid.stepZ.x, grid.stepZ.y, grid.stepZ.z, 0));
    m.setRow(3, openvdb::math::Vec4d(grid.origin.x, grid.origin.y, grid.origin.z, 1));
    auto transform = openvdb::math::Transform::createLinearTransform(m);
    for (int c = 0; c < BakedGrid::kChannels; ++c) {
        auto g = openvdb::FloatGrid::create(0.f);
        g->setName(kBakeChannels[c]);
        g->setTransform(transform->copy());
        g->setGridClass(openvdb::GRID_UNKNOWN);
        auto acc = g->getAccessor();
        for (int k = 0; k < grid.depth; ++k)
            for (int j = 0; j < grid.height; ++j)
                for (int i = 0; i < grid.width; ++i)
                    acc.setValue(openvdb::Coord(i, j, k), grid.at(i, j, k)[c]);
        for (const auto& [key, value] : grid.metadata)
            g->insertMeta("nenrin:" + key, openvdb::StringMetadata(value));
        grids.push_back(g);
    }
    try {
        openvdb::io::File file(out.temporaryPath());
        file.write(grids);
        file.close();
    } catch (const std::exception& e) {
        throw InputError(path, "", std::string("cannot write VDB: ") + e.what());
    }
    out.commit();
    return {path};
}

std::vector<std::string> writeDf3(const BakedGrid& grid, const std::string& path) {
    if (grid.width > 65535 || grid.height > 65535 || grid.depth > 65535)
        throw InputError(path, "", "df3 sizes are 16-bit: at most 65535 samples per axis");
    fs::path base = fs::path(path);
    std::string stem = (base.parent_path() / base.stem()).string();
    // R, G, B and knot as 16-bit densities in [0, 1].
    const std::vector<std::pair<const char*, int>> channels = {
        {"R", 0}, {"G", 1}, {"B", 2}, {"knot", 5}};
    std::vector<std::unique_ptr<AtomicOutput>> outputs;
    std::vector<std::string> written;
    for (auto [name, c] : channels) {
        std::string file = stem + "." + name + ".df3";
        outputs.push_back(std::make_unique<AtomicOutput>(file));
        std::ofstream f(outputs.back()->temporaryPath(), std::ios::binary);
        auto put16 = [&](unsigned v) {
            char b[2] = {static_cast<char>((v >> 8) & 0xff), static_cast<char>(v & 0xff)};
            f.write(b, 2);
        };
        put16(grid.width);
        put16(grid.height);
        put16(grid.depth);
        for (int k = 0; k < grid.depth; ++k)
            for (int j = 0; j < grid.height; ++j)
                for (int i = 0; i < grid.width; ++i) {
                    double v = std::clamp<double>(grid.at(i, j, k)[c], 0.0, 1.0);
                    put16(static_cast<unsigned>(std::lround(v * 65535)));
                }
        f.close();
        if (!f) throw InputError(file, "", "cannot write df3 file (disk full?)");
        written.push_back(file);
    }
    // The POV-Ray pigment that reassembles the colour (povray.md: exact to 2.8e-4), placed on
    // the bake box in POV-Ray's own coordinates (the caller maps tree to POV space).
    std::string inc = stem + ".inc";
    outputs.push_back(std::make_unique<AtomicOutput>(inc));
    {
        std::ofstream f(outputs.back()->temporaryPath());
        std::string name = base.stem().string();
        Vec3 size{grid.stepX.x * (grid.width - 1), grid.stepY.y * (grid.height - 1),
                  grid.stepZ.z * (grid.depth - 1)};
        f << fmt::format(
            "// nenrin wood baked to df3: {}x{}x{} samples over the tree-space box\n"
            "// <{}, {}, {}> .. <{}, {}, {}> (x, y, z as in tree space).\n"
            "#declare nenrin_wood = pigment {{ average pigment_map {{\n"
            "  [1 density_file df3 \"{}.R.df3\" interpolate 1 color_map {{[0 rgb 0][1 rgb "
            "<3,0,0>]}}]\n"
            "  [1 density_file df3 \"{}.G.df3\" interpolate 1 color_map {{[0 rgb 0][1 rgb "
            "<0,3,0>]}}]\n"
            "  [1 density_file df3 \"{}.B.df3\" interpolate 1 color_map {{[0 rgb 0][1 rgb "
            "<0,0,3>]}}]\n"
            "  }}\n"
            "  scale <{}, {}, {}> translate -1e-5\n"
            "  scale <{}, {}, {}> translate <{}, {}, {}>\n"
            "}}\n",
            grid.width, grid.height, grid.depth, grid.origin.x, grid.origin.y, grid.origin.z,
            grid.origin.x + size.x, grid.origin.y + size.y, grid.origin.z + size.z, name, name,
            name, double(grid.width) / (grid.width - 1), double(grid.height) / (grid.height - 1),
            double(grid.depth) / (grid.depth - 1), size.x, size.y, size.z, grid.origin.x,
            grid.origin.y, grid.origin.z);
        f.close();
        if (!f) throw InputError(inc, "", "cannot write POV-Ray include");
        written.push_back(inc);
    }
    for (auto& o : outputs) o->commit();
    return written;
}

std::vector<std::string> writeVolume(const BakedGrid& grid, const std::string& path) {
    checkOutputName(path, {".exr", ".vdb", ".df3"});
    std::string e = lowerExtension(path);
    if (e == ".exr") return writeExr(grid, path);
    if (e == ".vdb") return writeVdb(grid, path);
    return writeDf3(grid, path);
}

}  // namespace nenrin
