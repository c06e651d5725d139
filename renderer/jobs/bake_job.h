#pragma once
/// One slice or volume bake as a job: the skeleton and grain loaded (with the felling time the
/// caller asks for), the grid's metadata, a split job's part, the bake, the files written and
/// the statistics of the wood baked. `nenrin bake slice|volume` parse their arguments into it.

#include <optional>
#include <string>
#include <vector>

#include "renderer/bake/bake_specs.h"
#include "renderer/farm/split_job.h"

namespace nenrin {

/// What every bake takes besides where it samples.
struct BakeJob {
    std::string skeleton;
    std::string grain;   ///< empty: the default grain
    std::string output;  ///< slice: .exr; volume: .exr, .vdb or .df3
    std::string png;     ///< slice only: an 8-bit sRGB preview
    /// Slice only: the surface finish preset the cut shows (shader/finish.h; only "sawn"
    /// changes the albedo: saw marks).
    std::string finish = "oiled";
    /// Years, or "auto" (the years of the skeleton's ring_widths); empty: the grain file's.
    std::string fellingTime;
    int threads = 0;
    bool quiet = false;
    std::optional<PartNumber> part;  ///< a split job's part (--tile K/N)
};

struct BakeReport {
    std::vector<std::string> written;
    size_t samples = 0;
    size_t woodSamples = 0;                 ///< inside the felled log (A > 0)
    float tMin = 0, tMax = 0, knotMax = 0;  ///< over the wood samples
    /// Wall-clock seconds: reading the skeleton and grain and building the index and field;
    /// sampling; writing. The sampling rate counts the middle one only (loading a big
    /// skeleton file can take longer than sampling it).
    double setUpSeconds = 0, bakeSeconds = 0, writeSeconds = 0;
    /// One line: samples, times and rates, the share of wood, its T range and knots.
    std::string summary() const;
};

BakeReport runSliceBake(const BakeJob& job, const SliceSpec& slice);
/// `box` is the box as the caller wrote it, for the metadata.
BakeReport runVolumeBake(const BakeJob& job, const VolumeSpec& volume, const std::string& box);

}  // namespace nenrin
