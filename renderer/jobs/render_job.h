#pragma once
/// One render as a job: the scene with its overrides and the settings a caller changes, the
/// outputs checked before the long work, the EXR's metadata (and a split job's fingerprint),
/// the render and the files written. `nenrin render` and `nenrin batch` run it; they only
/// parse their arguments into a RenderJob and print what it reports.

#include <optional>
#include <string>
#include <vector>

#include "renderer/farm/split_job.h"
#include "renderer/path_tracer.h"

namespace nenrin {

/// What to render. 0, -1 or empty: the scene's own value.
struct RenderJob {
    std::string scene;
    std::string output;  ///< .exr
    std::string png;     ///< optional 8-bit sRGB preview
    int width = 0, height = 0;
    int spp = 0;
    double noiseThreshold = -1;
    int minSpp = -1;
    long long seed = -1;
    int threads = 0;
    bool quiet = false;
    bool denoise = false;            ///< the film denoised before it is written (--denoise)
    std::optional<PartNumber> part;  ///< a split job's part (--tile K/N)
    std::vector<std::string> sets;   ///< POINTER=VALUE scene overrides (--set)
};

struct RenderJobReport {
    std::vector<std::string> written;  ///< in the order written
    RenderSettings settings;           ///< as rendered
    std::optional<PartNumber> part;
    int firstRow = 0, rows = 0;  ///< the band of rows rendered (all of them unless a part)
    RenderStats stats;
    double denoiseSeconds = -1;  ///< -1: not denoised
    /// One line: size (or part), samples (adaptive: the mean), time and ray rates.
    std::string summary() const;
};

/// Renders and writes the job's outputs (atomically, inside the caller's output
/// transaction). InputErrors name the scene file or the command-line option at fault.
RenderJobReport runRenderJob(const RenderJob& job);

}  // namespace nenrin
