#pragma once
/// How much memory one nenrin job may take, and the check big allocations make first.
///
/// A job that would not fit is refused up front with its estimate and the limit, instead of
/// being killed by the kernel halfway (a `pov --volume 1024` once asked for 24 GiB). The limit
/// is `--max-memory` of the big commands, or by default 80 % of what the machine (or the
/// cgroup a batch system put the job in) has.

#include <cstdint>
#include <string>

namespace nenrin {

/// Physical memory, or the cgroup's memory.max when that is lower (SLURM, containers).
uint64_t availableMemoryBytes();

/// The limit in force: set by setMemoryLimit, else 80 % of availableMemoryBytes().
uint64_t memoryLimit();
void setMemoryLimit(uint64_t bytes);

/// "12.0 GiB", "512 MiB", ...
std::string formatBytes(double bytes);

/// Parses a size such as "8G", "8GiB", "512M", "1.5T" or plain bytes (K, M, G, T are powers of
/// 1024); 0 for a malformed, non-positive or absurd (> 1e18 bytes) text.
uint64_t parseByteSize(const std::string& text);

/// Throws InputError(`source`, "", ...) saying that `what` needs about `bytes` and the limit is
/// memoryLimit() (raise it with --max-memory), if bytes exceeds the limit.
void requireMemory(double bytes, const std::string& what, const std::string& source);

/// The same for output files of about `bytes` written into `folder`: refused when over the
/// memory limit (--max-memory bounds what a command may write too) or over the free space of
/// the folder's file system, naming the folder.
void requireOutputSpace(double bytes, const std::string& what, const std::string& folder);

}  // namespace nenrin
