#pragma once
/// The parts of a split job. `nenrin render --tile K/N` and `nenrin bake slice|volume --tile
/// K/N` write part K of N: an EXR holding one band of the frame's rows (its data window), with
/// the metadata of the whole job plus three keys that `nenrin merge` checks:
///   nenrin:part      "K/N"
///   nenrin:job       render | bake slice | bake volume
///   nenrin:job_hash  fingerprint of everything the pixels depend on (settings, the scene or
///                    skeleton as loaded, the bytes of every input file, the nenrin version)
/// Parts with different fingerprints never merge.

#include <map>
#include <string>
#include <vector>

#include "renderer/row_band.h"

namespace nenrin {

enum class JobKind { Render, BakeSlice, BakeVolume };

const char* jobKindName(JobKind kind);
/// Throws InputError (located at `file`) for anything but the names above.
JobKind parseJobKind(const std::string& name, const std::string& file);

/// "K/N" with 1 <= K <= N <= 4096; throws InputError located at `option`.
struct PartNumber {
    int part = 1, parts = 1;
};
PartNumber parsePartNumber(const std::string& text, const std::string& where,
                           const std::string& option);

/// Fingerprint of a job: its kind, the metadata it writes (settings), extra text (a scene as
/// loaded) and the bytes of its input files.
std::string jobFingerprint(JobKind kind, const std::map<std::string, std::string>& metadata,
                           const std::string& source, const std::vector<std::string>& inputFiles);

/// Adds the part keys to the metadata of a part.
void labelPart(std::map<std::string, std::string>& metadata, JobKind kind,
               const std::string& fingerprint, PartNumber number);

/// The metadata keys labelPart adds (merge removes them again).
const std::vector<std::string>& partKeys();

}  // namespace nenrin
