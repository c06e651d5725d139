#pragma once
/// `nenrin merge`: puts the parts of a split job (split_job.h) back together. The parts must
/// carry the same fingerprint, cover the frame exactly once and hold only finite numbers;
/// otherwise nothing is written and the error names the file (or the missing part). The
/// result is written by the same writer as the one-machine job, with the same metadata, so it
/// is byte-identical to it.

#include <string>
#include <vector>

#include "renderer/exr_file.h"
#include "renderer/farm/split_job.h"

namespace nenrin {

struct MergedJob {
    JobKind kind = JobKind::Render;
    int parts = 0;
    FloatExr image;  ///< the whole frame, metadata without the part keys
};

/// Reads and checks the parts; throws InputError on the first problem.
MergedJob mergeParts(const std::vector<std::string>& paths);

/// Checks the output names for this kind of job (before the parts are read): render and slice
/// write .exr (+ optional .png), volumes .exr, .vdb or .df3 (no png).
void checkMergeOutputs(const std::string& output, const std::string& png);

/// Writes the merged job as the one-machine command would; returns the files written.
std::vector<std::string> writeMergedJob(const MergedJob& job, const std::string& output,
                                        const std::string& png);

}  // namespace nenrin
