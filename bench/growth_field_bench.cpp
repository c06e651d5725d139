/// Growth-field throughput (samples/s) on seeded synthetic trees of 100 to 100k segments, as a
/// bake sees it: 8 cross-sections of 64 x 64 samples (0.3 m squares on the trunk axis, z from
/// 1 m to 18 m) listed as 8 x 8 tiles and evaluated 16 tiles per evaluateBatch call (as the
/// slice bake does: one index query per call, pruning per 8 x 8 tile) with parallelTiles on 1
/// or 2 threads, wall time. Trees, indices and sample points are built once and cached: the
/// timed loop only evaluates.
///   BM_GrowthField/<segments>/<threads>       Embree index and per-chain hierarchies
///   BM_GrowthFieldBrute/<segments>/<threads>  brute-force index: every query a plain loop
///                                             (the reference)
/// and on trees people use, the same sampling through the trunk between 10 % and 90 % of its
/// height, the square sized to the tree:
///   BM_GrowthField/gran1/<threads>                the CT-measured Gran_1 log (data/gran1)
///   BM_GrowthField/hayashi-sugi-order3/<threads>  `nenrin tree hayashi --preset sugi
///                                                 --max-order 3` (20 years, 34k segments)
///   BM_GrowthField/kanayama-cherry/<threads>      `nenrin tree kanayama --preset cherry`
///                                                 (15 years, 16k segments)
/// and BM_GrowthFieldBrute/... for each.

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
#include "skeleton/sources/hayashi/hayashi_conifer.h"
#include "skeleton/sources/hayashi/hayashi_options.h"
#include "skeleton/sources/kanayama/kanayama_growth.h"
#include "skeleton/sources/kanayama/kanayama_species.h"
#include "skeleton/sources/measured/gran1_import.h"
#include "skeleton/synthetic_tree.h"

namespace nenrin {
namespace {

constexpr int kTile = 8;        // samples per tile side
constexpr int kSide = 64;       // samples per cross-section side
constexpr int kSections = 8;    // cross-sections through the log
constexpr double kHalf = 0.15;  // m: half the side of a cross-section
constexpr double kZ0 = 1, kZ1 = 18;

/// Sample points, tile after tile: each run of kTile * kTile points is one tile. Sections of
/// side 2 * half centred on the pith, at kSections heights from z0 to z1.
std::vector<Vec3> sectionPoints(const Skeleton* skeleton, double half, double z0, double z1) {
    std::vector<Vec3> p;
    p.reserve(size_t(kSections) * kSide * kSide);
    const double step = 2 * half / (kSide - 1);
    for (int s = 0; s < kSections; ++s) {
        const double z = z0 + (z1 - z0) * s / (kSections - 1);
        const Vec3 pith = skeleton ? pithAtHeight(*skeleton, z) : Vec3{0, 0, z};
        for (int tj = 0; tj < kSide; tj += kTile)
            for (int ti = 0; ti < kSide; ti += kTile)
                for (int j = tj; j < tj + kTile; ++j)
                    for (int i = ti; i < ti + kTile; ++i)
                        p.push_back({pith.x - half + step * i, pith.y - half + step * j, z});
    }
    return p;
}

const std::vector<Vec3>& bakePoints() {
    static const std::vector<Vec3> points = sectionPoints(nullptr, kHalf, kZ0, kZ1);
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

void bake(benchmark::State& state, const GrowthField& field, const std::vector<Vec3>& points,
          int threads) {
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

void runBake(benchmark::State& state, IndexBackend backend) {
    bake(state, cachedField(static_cast<size_t>(state.range(0)), backend), bakePoints(),
         static_cast<int>(state.range(1)));
}

void BM_GrowthField(benchmark::State& state) { runBake(state, IndexBackend::Embree); }
void BM_GrowthFieldBrute(benchmark::State& state) { runBake(state, IndexBackend::BruteForce); }

void bakeArgs(benchmark::internal::Benchmark* b) {
    for (int64_t segments : {100, 1000, 10000, 100000})
        for (int64_t threads : {1, 2}) b->Args({segments, threads});
    b->UseRealTime()->Unit(benchmark::kMillisecond);
}

/// A tree people use, with its sample points: made once, on first use.
struct RealTree {
    Skeleton skeleton;
    std::vector<Vec3> points;
    std::map<IndexBackend, std::unique_ptr<SkeletonIndex>> indices;
    std::map<IndexBackend, std::unique_ptr<GrowthField>> fields;
};

Skeleton makeRealSkeleton(const std::string& name) {
    if (name == "gran1")
        return importGran1(std::string(NENRIN_SOURCE_DIR) + "/data/gran1/Gran_1").skeleton;
    if (name == "hayashi-sugi-order3") {
        HayashiOptions h = hayashiPreset("sugi");
        h.maxOrder = 3;
        return growHayashiConifer(h).skeleton;
    }
    return growKanayamaTree(kanayamaPreset("cherry"), [](int, int) {}).skeleton;
}

const GrowthField& realField(const std::string& name, IndexBackend backend,
                             const std::vector<Vec3>*& points) {
    static std::map<std::string, std::unique_ptr<RealTree>> cache;
    auto& tree = cache[name];
    if (!tree) {
        tree = std::make_unique<RealTree>();
        tree->skeleton = makeRealSkeleton(name);
        const SkeletonChain& trunk = tree->skeleton.chain(0);
        const Vec3 top =
            tree->skeleton.end(tree->skeleton.segment(trunk.firstSegment + trunk.segmentCount - 1));
        const Vec3 base = tree->skeleton.start(tree->skeleton.segment(trunk.firstSegment));
        // The square spans the trunk's largest radius at the lower section, and some bark.
        const double half = name == "gran1" ? 0.2 : name == "kanayama-cherry" ? 0.1 : 0.15;
        const double height = top.z - base.z;
        tree->points =
            sectionPoints(&tree->skeleton, half, base.z + 0.1 * height, base.z + 0.9 * height);
    }
    auto& field = tree->fields[backend];
    if (!field) {
        tree->indices[backend] = std::make_unique<SkeletonIndex>(tree->skeleton, backend);
        field = std::make_unique<GrowthField>(*tree->indices[backend], GrainParams{});
    }
    points = &tree->points;
    return *field;
}

void registerRealTrees() {
    for (const char* name : {"gran1", "hayashi-sugi-order3", "kanayama-cherry"})
        for (auto [prefix, backend] : {std::pair{"BM_GrowthField", IndexBackend::Embree},
                                       std::pair{"BM_GrowthFieldBrute", IndexBackend::BruteForce}})
            for (int threads : {1, 2}) {
                const std::string tree = name;
                const IndexBackend b = backend;
                benchmark::RegisterBenchmark(
                    (std::string(prefix) + "/" + name + "/" + std::to_string(threads)).c_str(),
                    [tree, b, threads](benchmark::State& state) {
                        const std::vector<Vec3>* points = nullptr;
                        const GrowthField& field = realField(tree, b, points);
                        bake(state, field, *points, threads);
                    })
                    ->UseRealTime()
                    ->Unit(benchmark::kMillisecond);
            }
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
    nenrin::registerRealTrees();
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
