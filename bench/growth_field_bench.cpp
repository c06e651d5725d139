/// Growth-field throughput (samples/s) on seeded synthetic trees of 100 to 100k segments, as a
/// bake sees it: 8 cross-sections of 64 x 64 samples (0.3 m squares on the trunk axis, z from
/// 1 m to 18 m) listed as 8 x 8 tiles and evaluated 16 tiles per evaluateBatch call (as the
/// slice bake does: one index query per call, pruning per 8 x 8 tile) with parallelTiles on 1
/// or 2 threads, wall time. Trees, indices and sample points are built once and cached: the
/// timed loop only evaluates.
///   BM_GrowthField/<segments>/<threads>       Embree index
///   BM_GrowthFieldBrute/<segments>/<threads>  brute-force index (the reference)

#include <benchmark/benchmark.h>
#include <unistd.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "grain/growth_field.h"
#include "renderer/parallel_tiles.h"
#include "skeleton/skeleton_index.h"
#include "skeleton/synthetic_tree.h"

namespace nenrin {
namespace {

constexpr int kTile = 8;        // samples per tile side
constexpr int kSide = 64;       // samples per cross-section side
constexpr int kSections = 8;    // cross-sections through the log
constexpr double kHalf = 0.15;  // m: half the side of a cross-section
constexpr double kZ0 = 1, kZ1 = 18;

/// Sample points, tile after tile: each run of kTile * kTile points is one tile.
const std::vector<Vec3>& bakePoints() {
    static const std::vector<Vec3> points = [] {
        std::vector<Vec3> p;
        p.reserve(size_t(kSections) * kSide * kSide);
        const double step = 2 * kHalf / (kSide - 1);
        for (int s = 0; s < kSections; ++s) {
            const double z = kZ0 + (kZ1 - kZ0) * s / (kSections - 1);
            for (int tj = 0; tj < kSide; tj += kTile)
                for (int ti = 0; ti < kSide; ti += kTile)
                    for (int j = tj; j < tj + kTile; ++j)
                        for (int i = ti; i < ti + kTile; ++i)
                            p.push_back({-kHalf + step * i, -kHalf + step * j, z});
        }
        return p;
    }();
    return points;
}

/// A tree of `segments` segments with a realistic branch density: a 200-segment trunk and at
/// most ~240 branches (a 20 m conifer grows ~12 per metre), the rest of the segments going
/// into finer branch polylines, as measured or simulated trees have.
SyntheticTreeOptions treeOptions(size_t segments) {
    SyntheticTreeOptions o{.seed = 1, .totalSegments = segments};
    o.segmentsPerBranch =
        std::max<size_t>(10, (segments - std::min(segments, o.trunkSegments)) / 240);
    return o;
}

/// A synthetic tree with its index and field; the index points into the skeleton, so the
/// fixture stays where it was made.
struct Fixture {
    Fixture(size_t segments, IndexBackend backend)
        : skeleton(makeSyntheticTree(treeOptions(segments))),
          index(skeleton, backend),
          field(index, GrainParams{}) {}
    Skeleton skeleton;
    SkeletonIndex index;
    GrowthField field;
};

const GrowthField& cachedField(size_t segments, IndexBackend backend) {
    static std::map<std::pair<size_t, IndexBackend>, std::unique_ptr<Fixture>> cache;
    auto& fixture = cache[{segments, backend}];
    if (!fixture) fixture = std::make_unique<Fixture>(segments, backend);
    return fixture->field;
}

void runBake(benchmark::State& state, IndexBackend backend) {
    const GrowthField& field = cachedField(static_cast<size_t>(state.range(0)), backend);
    const int threads = static_cast<int>(state.range(1));
    const std::vector<Vec3>& points = bakePoints();
    constexpr size_t kBatchSamples = 16 * kTile * kTile;
    const size_t batches = points.size() / kBatchSamples;
    for (auto _ : state) {
        parallelTiles(batches, threads, [&](size_t batch) {
            thread_local GrowthScratch scratch;
            thread_local std::vector<GrowthSample> samples(kBatchSamples);
            field.evaluateBatch(std::span(points).subspan(batch * kBatchSamples, kBatchSamples),
                                samples, scratch);
            benchmark::DoNotOptimize(samples.data());
        });
    }
    state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(points.size()));
}

void BM_GrowthField(benchmark::State& state) { runBake(state, IndexBackend::Embree); }
void BM_GrowthFieldBrute(benchmark::State& state) { runBake(state, IndexBackend::BruteForce); }

void bakeArgs(benchmark::internal::Benchmark* b) {
    for (int64_t segments : {100, 1000, 10000, 100000})
        for (int64_t threads : {1, 2}) b->Args({segments, threads});
    b->UseRealTime()->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_GrowthField)->Apply(bakeArgs);
BENCHMARK(BM_GrowthFieldBrute)->Apply(bakeArgs);

/// Google Benchmark appends "/real_time" to the names of wall-clock benchmarks; the case names
/// are a contract (BM_GrowthField/<segments>/<threads>), so the reporters drop that suffix.
template <class Base>
class ContractNames : public Base {
public:
    using Base::Base;
    void ReportRuns(const std::vector<benchmark::BenchmarkReporter::Run>& runs) override {
        std::vector<benchmark::BenchmarkReporter::Run> renamed = runs;
        for (auto& r : renamed) r.run_name.time_type.clear();
        Base::ReportRuns(renamed);
    }
};

}  // namespace
}  // namespace nenrin

/// The reporter for --benchmark_format / --benchmark_out_format (console, json, csv), with the
/// contract names: passing our own reporters replaces the library's, so it must honour them.
std::unique_ptr<benchmark::BenchmarkReporter> contractReporter(std::string_view format,
                                                               bool colour) {
    using namespace benchmark;
    if (format == "json") return std::make_unique<nenrin::ContractNames<JSONReporter>>();
    if (format == "csv") return std::make_unique<nenrin::ContractNames<CSVReporter>>();
    return std::make_unique<nenrin::ContractNames<ConsoleReporter>>(
        colour ? ConsoleReporter::OO_ColorTabular : ConsoleReporter::OO_Tabular);
}

int main(int argc, char** argv) {
    // Read before Initialize, which removes the flags it knows from argv.
    bool toFile = false;  // a file reporter is only allowed together with --benchmark_out
    std::string format = "console", outFormat = "json", colour = "auto";
    for (int i = 1; i < argc; ++i) {
        const std::string_view a(argv[i]);
        auto value = [&](std::string_view flag, std::string& out) {
            if (a.starts_with(flag)) out = std::string(a.substr(flag.size()));
        };
        toFile |= a.starts_with("--benchmark_out=");
        value("--benchmark_format=", format);
        value("--benchmark_out_format=", outFormat);
        value("--benchmark_color=", colour);
    }
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    const bool useColour =
        colour == "true" || colour == "yes" || (colour == "auto" && isatty(STDOUT_FILENO));
    auto display = contractReporter(format, useColour);
    auto file = toFile ? contractReporter(outFormat, false) : nullptr;
    benchmark::RunSpecifiedBenchmarks(display.get(), file.get());
    benchmark::Shutdown();
    return 0;
}
