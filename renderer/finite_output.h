#pragma once
/// The last guard of "no output holds a NaN or Inf": the writers (EXR, VDB, df3) check their
/// values before writing. Inputs are bounded where they are read, so a non-finite value here is
/// a nenrin bug; the job then fails with the place instead of passing a broken image on.

#include <cstddef>
#include <string>
#include <vector>

namespace nenrin {

/// `values` are channel-interleaved samples, `width` per row, rows from `firstRow`. Throws
/// std::runtime_error naming `path`, the sample (x, y) and the channel of the first
/// non-finite value.
void requireFiniteOutput(const float* values, size_t count,
                         const std::vector<std::string>& channels, int width, int firstRow,
                         const std::string& path);

/// The same for one channel of `pixels` samples, sample i at values[i * stride].
void requireFiniteChannel(const float* values, size_t stride, size_t pixels,
                          const std::string& channel, int width, int firstRow,
                          const std::string& path);

}  // namespace nenrin
