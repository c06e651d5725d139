#include "renderer/bake/grid_writers.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>

#include "renderer/bake/vdb_writer_abi.h"
#include "renderer/colour_management.h"
#include "renderer/exr_file.h"
#include "renderer/finite_output.h"
#include "util/atomic_output.h"
#include "util/content_hash.h"
#include "util/input_error.h"
#include "util/module_loader.h"

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
    // A band of layers is a band of the image's rows (a volume's z slices are stacked).
    const int rowsPerLayer = grid.isVolume() ? grid.height : 1;
    writeFloatExr(path, out.temporaryPath(), grid.width, grid.height * grid.depth,
                  {kBakeChannels.begin(), kBakeChannels.end()}, grid.data.data(), metadata,
                  {grid.layerBegin * rowsPerLayer, grid.storedEnd() * rowsPerLayer});
    out.commit();
    return {path};
}

namespace {

/// OpenVDB stamps every file with a random UUID (readers use it to spot the same file twice),
/// so the same bake would never give the same bytes. It is replaced by one made from the
/// content: the same grid gives the same file, a different grid another UUID.
void stampContentUuid(const BakedGrid& grid, const std::string& file, const std::string& path) {
    // Header: magic (8 bytes), file version (4), library version (4 + 4), "has grid offsets"
    // (1), then the UUID as 36 ASCII characters 8-4-4-4-12.
    constexpr std::streamoff kUuidOffset = 21;
    constexpr size_t kUuidSize = 36;
    std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
    std::string uuid(kUuidSize, '\0');
    f.seekg(kUuidOffset);
    f.read(uuid.data(), kUuidSize);
    const bool looksRight =
        f && uuid[8] == '-' && uuid[13] == '-' && uuid[18] == '-' && uuid[23] == '-';
    if (!looksRight)
        throw InputError(path, "", "unexpected OpenVDB header: no UUID where expected");
    ContentHash hash;
    hash.add(std::string_view(reinterpret_cast<const char*>(grid.data.data()),
                              grid.data.size() * sizeof(float)));
    for (const auto& [key, value] : grid.metadata) hash.add(key + "=" + value);
    const std::string h = hash.hex();
    const std::string stamped = h.substr(0, 8) + "-" + h.substr(8, 4) + "-" + h.substr(12, 4) +
                                "-" + h.substr(16, 4) + "-" + h.substr(20, 12);
    f.seekp(kUuidOffset);
    f.write(stamped.data(), kUuidSize);
    f.close();
    if (!f) throw InputError(path, "", "cannot write the VDB (disk full?)");
}

void requireFinite(const BakedGrid& grid, const std::string& path) {
    requireFiniteOutput(grid.data.data(), grid.data.size(),
                        std::vector<std::string>(kBakeChannels.begin(), kBakeChannels.end()),
                        grid.width, 0, path);
}

}  // namespace

std::vector<std::string> writeVdb(const BakedGrid& grid, const std::string& path) {
    if (!grid.whole()) throw std::invalid_argument("writeVdb: a band of a grid");
    requireFinite(grid, path);
    const auto write = reinterpret_cast<NenrinVdbWriteFn>(
        moduleSymbol("libnenrin_vdb_writer.so", NENRIN_VDB_MODULE, "nenrin_vdb_write", path));
    AtomicOutput out(path);
    NenrinVdbGrid g{};
    g.width = grid.width;
    g.height = grid.height;
    g.depth = grid.depth;
    g.channels = BakedGrid::kChannels;
    g.data = grid.data.data();
    g.channelNames = kBakeChannels.data();
    const Vec3 rows[4] = {grid.stepX, grid.stepY, grid.stepZ, grid.origin};
    for (int r = 0; r < 4; ++r) {
        g.indexToWorld[r * 4 + 0] = rows[r].x;
        g.indexToWorld[r * 4 + 1] = rows[r].y;
        g.indexToWorld[r * 4 + 2] = rows[r].z;
        g.indexToWorld[r * 4 + 3] = r == 3 ? 1 : 0;
    }
    std::vector<const char*> keys, values;
    for (const auto& [key, value] : grid.metadata) {
        keys.push_back(key.c_str());
        values.push_back(value.c_str());
    }
    g.metadataKeys = keys.data();
    g.metadataValues = values.data();
    g.metadataCount = static_cast<int>(keys.size());
    char error[1024] = {};
    if (write(out.temporaryPath().c_str(), &g, error, sizeof error) != 0)
        throw InputError(path, "", std::string("cannot write VDB: ") + error);
    stampContentUuid(grid, out.temporaryPath(), path);
    out.commit();
    return {path};
}

std::vector<std::string> writeDf3(const BakedGrid& grid, const std::string& path) {
    if (!grid.whole()) throw std::invalid_argument("writeDf3: a band of a grid");
    requireFinite(grid, path);
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
    // The POV-Ray pigment that reassembles the colour (docs/design/povray.md: exact to 2.8e-4),
    // placed on the bake box in POV-Ray's own coordinates (the caller maps tree to POV space).
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

void writeSlicePreviewPng(const BakedGrid& grid, const std::string& path) {
    std::vector<float> rgb;
    rgb.reserve(grid.sampleCount() * 3);
    for (size_t i = 0; i < grid.sampleCount(); ++i)
        for (int c = 0; c < 3; ++c)
            rgb.push_back(grid.data[i * BakedGrid::kChannels + c] *
                          grid.data[i * BakedGrid::kChannels + 3]);
    writePreviewPng(path, rgb, grid.width, grid.height);
}

std::vector<std::string> writeVolume(const BakedGrid& grid, const std::string& path) {
    checkOutputName(path, {".exr", ".vdb", ".df3"});
    std::string e = lowerExtension(path);
    if (e == ".exr") return writeExr(grid, path);
    if (e == ".vdb") return writeVdb(grid, path);
    return writeDf3(grid, path);
}

}  // namespace nenrin
