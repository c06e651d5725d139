#include "renderer/farm/split_job.h"

#include <fmt/format.h>

#include <charconv>

#include "util/content_hash.h"
#include "util/input_error.h"

namespace nenrin {

namespace {
constexpr int kMaxParts = 4096;
}

const char* jobKindName(JobKind kind) {
    switch (kind) {
        case JobKind::Render:
            return "render";
        case JobKind::BakeSlice:
            return "bake slice";
        case JobKind::BakeVolume:
            return "bake volume";
    }
    return "?";
}

JobKind parseJobKind(const std::string& name, const std::string& file) {
    for (JobKind k : {JobKind::Render, JobKind::BakeSlice, JobKind::BakeVolume})
        if (name == jobKindName(k)) return k;
    throw InputError(file, "nenrin:job",
                     fmt::format("\"{}\": expected render, bake slice or bake volume", name));
}

PartNumber parsePartNumber(const std::string& text, const std::string& where,
                           const std::string& option) {
    PartNumber n;
    const char* end = text.data() + text.size();
    auto [slash, e1] = std::from_chars(text.data(), end, n.part);
    bool ok = e1 == std::errc() && slash != end && *slash == '/';
    if (ok) {
        auto [last, e2] = std::from_chars(slash + 1, end, n.parts);
        ok = e2 == std::errc() && last == end;
    }
    if (!ok || n.part < 1 || n.part > n.parts || n.parts > kMaxParts)
        throw InputError(where, option,
                         fmt::format("\"{}\": expected K/N, part K of N with 1 <= K <= N <= {}",
                                     text, kMaxParts));
    return n;
}

std::string jobFingerprint(JobKind kind, const std::map<std::string, std::string>& metadata,
                           const std::string& source, const std::vector<std::string>& inputFiles) {
    ContentHash hash;
    hash.add(jobKindName(kind));
    for (const auto& [key, value] : metadata) {
        hash.add(key);
        hash.add(value);
    }
    hash.add(source);
    for (const std::string& file : inputFiles) {
        hash.add(file);
        hash.addFile(file);
    }
    return hash.hex();
}

void labelPart(std::map<std::string, std::string>& metadata, JobKind kind,
               const std::string& fingerprint, PartNumber number) {
    metadata["part"] = fmt::format("{}/{}", number.part, number.parts);
    metadata["job"] = jobKindName(kind);
    metadata["job_hash"] = fingerprint;
}

const std::vector<std::string>& partKeys() {
    static const std::vector<std::string> keys = {"part", "job", "job_hash"};
    return keys;
}

}  // namespace nenrin
