// The shader plugin as a host sees it: libnenrin_shader.so (NENRIN_SHADER_PLUGIN) is loaded
// with dlopen and every entry point looked up with dlsym. Its results must be the C++ API's
// (WoodShader::evaluateSurface, linked here statically as the reference) converted to float;
// every misuse and bad input must come back as a status and a message, never an abort; the
// library must export nothing but the C ABI and must not drag in the renderer's dependencies.

#include <dlfcn.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "grain/grain_params.h"
#include "grain/grown_tree.h"
#include "nenrin/shader.h"
#include "shader/finish.h"
#include "shader/wood_shader.h"
#include "skeleton/skeleton_file.h"
#include "skeleton/skeleton_index.h"

namespace nenrin {
namespace {

const std::string kSourceDir = NENRIN_SOURCE_DIR;

/// The plugin's entry points, looked up by name as a host would (signatures from the header).
struct Plugin {
    void* handle = nullptr;
    std::string error;
    decltype(&nenrin_shader_abi_version) abiVersion = nullptr;
    decltype(&nenrin_shader_version) version = nullptr;
    decltype(&nenrin_shader_create) create = nullptr;
    decltype(&nenrin_shader_evaluate) evaluate = nullptr;
    decltype(&nenrin_shader_destroy) destroy = nullptr;
};

template <class F>
void lookUp(Plugin& p, F& f, const char* name) {
    f = reinterpret_cast<F>(dlsym(p.handle, name));
    if (!f) p.error += std::string("dlsym(") + name + ") failed; ";
}

/// Loaded once for the whole binary and never unloaded.
const Plugin& plugin() {
    static const Plugin loaded = [] {
        Plugin p;
        p.handle = dlopen(NENRIN_SHADER_PLUGIN, RTLD_NOW | RTLD_LOCAL);
        if (!p.handle) {
            const char* e = dlerror();
            p.error = e ? e : "dlopen failed";
            return p;
        }
        lookUp(p, p.abiVersion, "nenrin_shader_abi_version");
        lookUp(p, p.version, "nenrin_shader_version");
        lookUp(p, p.create, "nenrin_shader_create");
        lookUp(p, p.evaluate, "nenrin_shader_evaluate");
        lookUp(p, p.destroy, "nenrin_shader_destroy");
        return p;
    }();
    return loaded;
}

/// A created shader, destroyed through the plugin.
struct ShaderDeleter {
    void operator()(nenrin_shader* s) const { plugin().destroy(s); }
};
using ShaderPtr = std::unique_ptr<nenrin_shader, ShaderDeleter>;

/// The result of a create call.
struct Created {
    nenrin_status status;
    ShaderPtr shader;
    std::string message;
};

Created create(const std::string& description, const char* base = kSourceDir.c_str()) {
    char message[1024];
    std::memset(message, 'x', sizeof message);
    nenrin_shader* raw = reinterpret_cast<nenrin_shader*>(&message);  // must be overwritten
    nenrin_status st = plugin().create(description.c_str(), base, &raw, message, sizeof message);
    return {st, ShaderPtr(raw), message};
}

/// Tree-space points, x y z interleaved, as the plugin takes them.
using Points = std::vector<float>;

/// A cross-section at height z: n x n points over [-half, half]^2.
Points crossSection(float z, float half, int n) {
    Points p;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            p.push_back(-half + 2 * half * (i + 0.5f) / n);
            p.push_back(-half + 2 * half * (j + 0.5f) / n);
            p.push_back(z);
        }
    return p;
}

/// A flat-sawn board in the plane y = offset: nx x nz points over x in [-half, half],
/// z in [bottom, top].
Points board(float offset, float half, float bottom, float top, int nx, int nz) {
    Points p;
    for (int j = 0; j < nz; ++j)
        for (int i = 0; i < nx; ++i) {
            p.push_back(-half + 2 * half * (i + 0.5f) / nx);
            p.push_back(offset);
            p.push_back(bottom + (top - bottom) * (j + 0.5f) / nz);
        }
    return p;
}

/// The conifer cut at 1.13 m through a whorl of dead knots (out to where the felled log ends),
/// and a board 45 mm off the pith past the knot of the branch that points towards +y.
Points coniferSamples() {
    Points p = crossSection(1.13f, 0.15f, 48);
    Points b = board(0.045f, 0.1f, 0.9f, 1.5f, 32, 64);
    p.insert(p.end(), b.begin(), b.end());
    return p;
}

/// Footprint diameters 0 .. 6 mm, a different one for neighbouring points.
std::vector<float> footprintsFor(const Points& points) {
    std::vector<float> d(points.size() / 3);
    for (size_t i = 0; i < d.size(); ++i) d[i] = static_cast<float>(i % 5) * 0.0015f;
    return d;
}

std::vector<nenrin_shading_result> evaluate(const nenrin_shader* shader, const Points& points,
                                            const float* footprints = nullptr) {
    std::vector<nenrin_shading_result> out(points.size() / 3);
    char message[512];
    nenrin_status st = plugin().evaluate(shader, out.size(), points.data(), footprints, out.data(),
                                         message, sizeof message);
    EXPECT_EQ(st, NENRIN_OK) << message;
    EXPECT_STREQ(message, "");
    return out;
}

/// The same tree through the C++ API.
class Reference {
public:
    Reference(Skeleton skeleton, GrainParams grain, const std::string& finishName)
        : tree_(std::move(skeleton), std::move(grain)) {
        Finish finish;
        EXPECT_TRUE(finishPreset(finishName, finish));
        shader_ = std::make_unique<WoodShader>(tree_.field(), finish);
    }

    /// The C++ API's answers, and the roughness the plugin reports for the finish.
    struct Expected {
        std::vector<WoodSurfaceSample> samples;
        double roughness;
    };

    Expected evaluate(const Points& points, const float* diameters = nullptr) const {
        const size_t n = points.size() / 3;
        std::vector<Vec3> p(n);
        for (size_t i = 0; i < n; ++i) p[i] = {points[3 * i], points[3 * i + 1], points[3 * i + 2]};
        std::vector<SurfaceFootprint> f;
        if (diameters)
            for (size_t i = 0; i < n; ++i) f.push_back({{}, {}, diameters[i], {}});
        std::vector<WoodSurfaceSample> out(n);
        WoodScratch scratch;
        shader_->evaluateSurface(p, f, out, scratch);
        return {out, shader_->finish().surfaceRoughness()};
    }

private:
    GrownTree tree_;
    std::unique_ptr<WoodShader> shader_;
};

/// Equal after float conversion, or within 1e-6 relative.
::testing::AssertionResult sameValue(const char* name, size_t i, double expected, float actual) {
    if (static_cast<float>(expected) == actual ||
        std::abs(actual - expected) <= 1e-6 * std::abs(expected))
        return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "point " << i << ": " << name << " is " << actual
                                         << ", the C++ API gives " << expected;
}

/// Every field of every result against the reference; returns the number of mismatches.
int compare(const Reference::Expected& reference,
            const std::vector<nenrin_shading_result>& actual) {
    const std::vector<WoodSurfaceSample>& expected = reference.samples;
    EXPECT_EQ(expected.size(), actual.size());
    int bad = 0;
    auto check = [&](const char* name, size_t i, double e, float a) {
        auto r = sameValue(name, i, e, a);
        if (!r && bad++ < 20) ADD_FAILURE() << r.message();
    };
    for (size_t i = 0; i < std::min(expected.size(), actual.size()); ++i) {
        const WoodSurfaceSample& e = expected[i];
        const nenrin_shading_result& a = actual[i];
        // The ABI's albedo is black outside the felled log (docs/plugin.md); the C++ API
        // gives the bark there.
        const Rgb albedo = e.coverage > 0 ? e.albedo : Rgb{};
        check("albedo[0]", i, albedo.r, a.albedo[0]);
        check("albedo[1]", i, albedo.g, a.albedo[1]);
        check("albedo[2]", i, albedo.b, a.albedo[2]);
        check("roughness", i, reference.roughness, a.roughness);
        check("fibre[0]", i, e.fibre.x, a.fibre[0]);
        check("fibre[1]", i, e.fibre.y, a.fibre[1]);
        check("fibre[2]", i, e.fibre.z, a.fibre[2]);
        check("T", i, e.T, a.T);
        check("knot", i, e.knot, a.knot);
        check("dead_knot", i, e.deadKnot, a.dead_knot);
        check("coverage", i, e.coverage, a.coverage);
        check("late_wood", i, e.lateWood, a.late_wood);
    }
    return bad;
}

std::string coniferDescription(const std::string& finish = "oiled") {
    return R"({"skeleton": "scenes/skeletons/conifer.json", "grain": "scenes/grain/species/norway-spruce.json",
               "finish": ")" +
           finish + R"("})";
}

Reference coniferReference(const std::string& finish = "oiled") {
    return Reference(loadSkeletonFile(kSourceDir + "/scenes/skeletons/conifer.json"),
                     loadGrainFile(kSourceDir + "/scenes/grain/species/norway-spruce.json"),
                     finish);
}

class ShaderPlugin : public ::testing::Test {
protected:
    void SetUp() override {
        const Plugin& p = plugin();
        ASSERT_NE(p.handle, nullptr) << p.error;
        ASSERT_TRUE(p.abiVersion && p.version && p.create && p.evaluate && p.destroy) << p.error;
    }
};

TEST_F(ShaderPlugin, ReportsItsVersions) {
    EXPECT_EQ(NENRIN_SHADER_ABI_VERSION, 1);
    EXPECT_EQ(plugin().abiVersion(), NENRIN_SHADER_ABI_VERSION);
    ASSERT_NE(plugin().version(), nullptr);
    EXPECT_STREQ(plugin().version(), NENRIN_VERSION);
}

TEST_F(ShaderPlugin, MatchesTheCxxApiOnTheConifer) {
    Created c = create(coniferDescription());
    ASSERT_EQ(c.status, NENRIN_OK) << c.message;
    ASSERT_NE(c.shader, nullptr);
    EXPECT_EQ(c.message, "");
    Reference reference = coniferReference();
    const Points points = coniferSamples();
    ASSERT_GT(points.size() / 3, 1000u);

    // Point samples.
    std::vector<nenrin_shading_result> plain = evaluate(c.shader.get(), points);
    EXPECT_EQ(compare(reference.evaluate(points), plain), 0);
    // With footprints.
    const std::vector<float> footprints = footprintsFor(points);
    std::vector<nenrin_shading_result> filtered =
        evaluate(c.shader.get(), points, footprints.data());
    EXPECT_EQ(compare(reference.evaluate(points, footprints.data()), filtered), 0);

    // The samples cover what matters: living and dead knots, wood and outside the felled log,
    // and footprints that change the filtered ring profile.
    int knots = 0, deadKnots = 0, outside = 0, inside = 0, changed = 0;
    for (size_t i = 0; i < plain.size(); ++i) {
        const nenrin_shading_result& r = plain[i];
        knots += r.knot > 0.5f;
        deadKnots += r.dead_knot > 0.5f;
        outside += r.coverage == 0;
        inside += r.coverage == 1;
        changed += r.late_wood != filtered[i].late_wood;
        EXPECT_EQ(r.roughness, 0.12f);
        EXPECT_NEAR(std::hypot(r.fibre[0], r.fibre[1], r.fibre[2]), 1, 1e-5) << i;
        EXPECT_GE(r.dead_knot, 0);
        EXPECT_LE(r.dead_knot, r.knot + 1e-6f);
    }
    EXPECT_GT(knots, 10);
    EXPECT_GT(deadKnots, 10);
    EXPECT_GT(outside, 10);
    EXPECT_GT(inside, 500);
    EXPECT_GT(changed, 100);
}

TEST_F(ShaderPlugin, LargeBatchesMatchTheCxxApi) {
    // More points than one internal chunk, in one call.
    Created c = create(coniferDescription("matte"));
    ASSERT_EQ(c.status, NENRIN_OK) << c.message;
    const Points points = crossSection(1.7f, 0.12f, 100);
    const std::vector<float> footprints = footprintsFor(points);
    EXPECT_EQ(compare(coniferReference("matte").evaluate(points, footprints.data()),
                      evaluate(c.shader.get(), points, footprints.data())),
              0);
}

TEST_F(ShaderPlugin, ResultsDoNotDependOnBatching) {
    Created c = create(coniferDescription());
    ASSERT_EQ(c.status, NENRIN_OK) << c.message;
    const Points points = coniferSamples();
    const std::vector<float> footprints = footprintsFor(points);
    const std::vector<nenrin_shading_result> whole =
        evaluate(c.shader.get(), points, footprints.data());
    for (size_t batch : {size_t{1}, size_t{37}}) {
        std::vector<nenrin_shading_result> pieces(whole.size());
        for (size_t begin = 0; begin < whole.size(); begin += batch) {
            size_t n = std::min(batch, whole.size() - begin);
            ASSERT_EQ(
                plugin().evaluate(c.shader.get(), n, points.data() + 3 * begin,
                                  footprints.data() + begin, pieces.data() + begin, nullptr, 0),
                NENRIN_OK);
        }
        EXPECT_EQ(std::memcmp(pieces.data(), whole.data(), whole.size() * sizeof whole[0]), 0)
            << "batches of " << batch;
    }
}

TEST_F(ShaderPlugin, InlineSkeletonAndGrain) {
    const char* skeleton =
        R"({"elongation_speed": 0.5, "trunk": {"points": [[0, 0, 0], [0, 0, 4]]}})";
    const char* grain = R"({"radial_speed": 0.005, "colour": {"micro": {"amplitude": 0}}})";
    Created c = create(std::string(R"({"skeleton": )") + skeleton + R"(, "grain": )" + grain +
                           R"(, "finish": "varnished"})",
                       nullptr);
    ASSERT_EQ(c.status, NENRIN_OK) << c.message;
    Reference reference(parseSkeleton(nlohmann::json::parse(skeleton), "inline"),
                        parseGrain(nlohmann::json::parse(grain), "inline"), "varnished");
    const Points points = crossSection(1.0f, 0.1f, 20);
    std::vector<nenrin_shading_result> out = evaluate(c.shader.get(), points);
    EXPECT_EQ(compare(reference.evaluate(points), out), 0);
    for (size_t i = 0; i < out.size(); ++i) {
        // The analytic case: T = z / Sa + r / Sb; rings are cones, and the fibres lie in them,
        // tilted from the trunk's axis by atan(Sb / Sa); no knots.
        double r = std::hypot(points[3 * i], points[3 * i + 1]);
        EXPECT_NEAR(out[i].T, 1.0 / 0.5 + r / 0.005, 1e-4) << i;
        EXPECT_NEAR(std::abs(out[i].fibre[2]), 0.5 / std::hypot(0.5, 0.005), 1e-6) << i;
        EXPECT_EQ(out[i].knot, 0);
        EXPECT_EQ(out[i].coverage, 1);
        EXPECT_EQ(out[i].roughness, 0.03f);
    }
}

TEST_F(ShaderPlugin, GrainAndFinishAreOptional) {
    Created c = create(R"({"skeleton": "scenes/skeletons/conifer.json"})");
    ASSERT_EQ(c.status, NENRIN_OK) << c.message;
    Reference reference(loadSkeletonFile(kSourceDir + "/scenes/skeletons/conifer.json"),
                        GrainParams{}, "oiled");
    const Points points = board(0.03f, 0.08f, 1.0f, 1.3f, 8, 16);
    EXPECT_EQ(compare(reference.evaluate(points), evaluate(c.shader.get(), points)), 0);
}

TEST_F(ShaderPlugin, AbsolutePathsIgnoreTheBaseDirectory) {
    Created c = create(R"({"skeleton": ")" + kSourceDir +
                           R"(/scenes/skeletons/straight-trunk.json", "finish": "matte"})",
                       "/nonexistent");
    ASSERT_EQ(c.status, NENRIN_OK) << c.message;
    EXPECT_EQ(evaluate(c.shader.get(), crossSection(1, 0.05f, 2))[0].roughness, 0.45f);
}

// --- Bad descriptions: NENRIN_ERROR_INPUT, a message like every nenrin error, no shader.

void expectInputError(const Created& c, std::initializer_list<const char*> mentions) {
    EXPECT_EQ(c.status, NENRIN_ERROR_INPUT) << c.message;
    EXPECT_EQ(c.shader, nullptr);
    for (const char* m : mentions) EXPECT_NE(c.message.find(m), std::string::npos) << c.message;
}

TEST_F(ShaderPlugin, MalformedJsonGivesLineAndColumn) {
    expectInputError(create("{\"skeleton\": \"scenes/skeletons/conifer.json\",\n  \"finish\": }"),
                     {"<description>", "line 2, column 13", "invalid JSON"});
    expectInputError(create(""), {"<description>", "line 1, column 1"});
    expectInputError(create("[1, 2]"), {"<description>", "expected an object"});
}

TEST_F(ShaderPlugin, MissingFilesAreNamed) {
    expectInputError(create(R"({"skeleton": "scenes/skeletons/no-such-tree.json"})"),
                     {(kSourceDir + "/scenes/skeletons/no-such-tree.json").c_str(), "cannot open"});
    expectInputError(create(R"({"skeleton": "scenes/skeletons/conifer.json",
                                "grain": "scenes/grain/no-such-grain.json"})"),
                     {(kSourceDir + "/scenes/grain/no-such-grain.json").c_str()});
    // Without a base directory, relative to the current directory.
    expectInputError(create(R"({"skeleton": "no-such-tree.json"})", nullptr),
                     {"no-such-tree.json: ", "cannot open"});
}

TEST_F(ShaderPlugin, UnknownKeysAndValuesAreErrors) {
    expectInputError(
        create(R"({"skeleton": "scenes/skeletons/conifer.json", "colour": [1, 0, 0]})"),
        {"<description>: colour: unknown key"});
    expectInputError(create(R"({"skeleton": "scenes/skeletons/conifer.json", "finish": "glossy"})"),
                     {"<description>: finish: ", "matte, oiled, varnished", "\"glossy\""});
    expectInputError(create(R"({"grain": "scenes/grain/species/norway-spruce.json"})"),
                     {"<description>: skeleton: missing"});
    expectInputError(create(R"({"skeleton": 3})"), {"<description>: skeleton: ", "found a number"});
    expectInputError(create(R"({"skeleton": ""})"), {"<description>: skeleton: ", "empty"});
    expectInputError(create(R"({"skeleton": "scenes/skeletons/conifer.json", "finish": 1})"),
                     {"<description>: finish: expected a string"});
}

TEST_F(ShaderPlugin, ErrorsInsideInlineObjectsAreLocatedInTheDescription) {
    expectInputError(create(R"({"skeleton": {"trunk": {"points": [[0, 0, 0]]}}})"),
                     {"<description>: skeleton.trunk.points: expected at least 2"});
    expectInputError(create(R"({"skeleton": {"trunk": {"points": [[0, 0, 0], [0, 0, 1]]}},
                                "grain": {"radial_sped": 0.004}})"),
                     {"<description>: grain.radial_sped: unknown key"});
    expectInputError(create(R"({"skeleton": {"trunk": {"points": [[0, 0, 0], [0, 0, 4]]},
                                             "branches": [{"height": 9, "azimuth": 0}]}})"),
                     {"<description>: skeleton.branches[0].height: ", "off the trunk"});
}

TEST_F(ShaderPlugin, NullArgumentsToCreate) {
    char message[256];
    nenrin_shader* s = nullptr;
    EXPECT_EQ(plugin().create(nullptr, nullptr, &s, message, sizeof message),
              NENRIN_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(s, nullptr);
    EXPECT_NE(std::strstr(message, "json_description"), nullptr) << message;
    EXPECT_EQ(plugin().create(coniferDescription().c_str(), kSourceDir.c_str(), nullptr, message,
                              sizeof message),
              NENRIN_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::strstr(message, "out"), nullptr) << message;
}

// --- Bad evaluation arguments: NENRIN_ERROR_INVALID_ARGUMENT, out untouched.

class ShaderPluginEvaluate : public ShaderPlugin {
protected:
    void SetUp() override {
        ShaderPlugin::SetUp();
        if (HasFatalFailure()) return;
        Created c = create(R"({"skeleton": "scenes/skeletons/straight-trunk.json"})");
        ASSERT_EQ(c.status, NENRIN_OK) << c.message;
        shader_ = std::move(c.shader);
        points_ = crossSection(1, 0.05f, 4);
        out_.resize(points_.size() / 3);
        std::memset(out_.data(), 0x5a, out_.size() * sizeof(nenrin_shading_result));
    }

    /// Calls evaluate with the fixture's points and output; the message lands in message_.
    nenrin_status call(const float* footprints = nullptr) {
        return plugin().evaluate(shader_.get(), out_.size(), points_.data(), footprints,
                                 out_.data(), message_, sizeof message_);
    }

    bool outUntouched() const {
        for (const nenrin_shading_result& r : out_) {
            const auto* bytes = reinterpret_cast<const unsigned char*>(&r);
            for (size_t i = 0; i < sizeof r; ++i)
                if (bytes[i] != 0x5a) return false;
        }
        return true;
    }

    ShaderPtr shader_;
    Points points_;
    std::vector<nenrin_shading_result> out_;
    char message_[512] = {};
};

TEST_F(ShaderPluginEvaluate, NanOrInfinitePointsAreNamedAndNothingIsWritten) {
    points_[3 * 7 + 1] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(call(), NENRIN_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::strstr(message_, "point 7 "), nullptr) << message_;
    EXPECT_NE(std::strstr(message_, "nan"), nullptr) << message_;
    EXPECT_TRUE(outUntouched());

    points_[3 * 7 + 1] = 0;
    points_[3 * 12 + 2] = -std::numeric_limits<float>::infinity();
    EXPECT_EQ(call(), NENRIN_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::strstr(message_, "point 12 "), nullptr) << message_;
    EXPECT_TRUE(outUntouched());
}

TEST_F(ShaderPluginEvaluate, BadFootprintsAreNamed) {
    std::vector<float> footprints(out_.size(), 0.001f);
    footprints[5] = -0.001f;
    EXPECT_EQ(call(footprints.data()), NENRIN_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::strstr(message_, "footprint 5 "), nullptr) << message_;
    footprints[5] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(call(footprints.data()), NENRIN_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::strstr(message_, "footprint 5 "), nullptr) << message_;
    EXPECT_TRUE(outUntouched());
}

TEST_F(ShaderPluginEvaluate, NullPointers) {
    EXPECT_EQ(plugin().evaluate(shader_.get(), out_.size(), points_.data(), nullptr, nullptr,
                                message_, sizeof message_),
              NENRIN_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::strstr(message_, "out is NULL"), nullptr) << message_;
    EXPECT_EQ(plugin().evaluate(shader_.get(), out_.size(), nullptr, nullptr, out_.data(), message_,
                                sizeof message_),
              NENRIN_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::strstr(message_, "points is NULL"), nullptr) << message_;
    EXPECT_EQ(plugin().evaluate(nullptr, out_.size(), points_.data(), nullptr, out_.data(),
                                message_, sizeof message_),
              NENRIN_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::strstr(message_, "shader is NULL"), nullptr) << message_;
    EXPECT_TRUE(outUntouched());
}

TEST_F(ShaderPluginEvaluate, CountZeroIsFine) {
    std::strcpy(message_, "stale");
    EXPECT_EQ(
        plugin().evaluate(shader_.get(), 0, nullptr, nullptr, nullptr, message_, sizeof message_),
        NENRIN_OK);
    EXPECT_STREQ(message_, "");
}

TEST_F(ShaderPluginEvaluate, ExtremeFinitePointsDoNotFail) {
    const float big = std::numeric_limits<float>::max();
    const float tiny = std::numeric_limits<float>::denorm_min();
    points_ = {big, big, big, -big, 0, -big, tiny, -tiny, tiny, 0, 0, 0, 1e6f, -1e6f, 3};
    out_.resize(points_.size() / 3);
    EXPECT_EQ(call(), NENRIN_OK) << message_;
    std::vector<float> footprints = {big, 0, tiny, 1e3f, 1};
    EXPECT_EQ(call(footprints.data()), NENRIN_OK) << message_;
    // T may overflow to infinity out there, but nothing turns into NaN.
    for (const nenrin_shading_result& r : out_) {
        for (float v : {r.albedo[0], r.albedo[1], r.albedo[2], r.fibre[0], r.fibre[1], r.fibre[2],
                        r.T, r.knot, r.coverage, r.late_wood})
            EXPECT_FALSE(std::isnan(v));
    }
}

// --- Messages.

TEST_F(ShaderPlugin, MessagesAreTruncatedAndAlwaysTerminated) {
    const std::string bad = R"({"skeleton": "scenes/skeletons/conifer.json", "finish": "glossy"})";
    const std::string full = create(bad).message;
    ASSERT_GT(full.size(), 20u);
    nenrin_shader* s = nullptr;
    char buffer[16];

    std::memset(buffer, 'x', sizeof buffer);
    EXPECT_EQ(plugin().create(bad.c_str(), kSourceDir.c_str(), &s, buffer, 8), NENRIN_ERROR_INPUT);
    EXPECT_EQ(std::string(buffer), full.substr(0, 7));
    EXPECT_EQ(buffer[8], 'x');  // nothing past message_size

    std::memset(buffer, 'x', sizeof buffer);
    EXPECT_EQ(plugin().create(bad.c_str(), kSourceDir.c_str(), &s, buffer, 1), NENRIN_ERROR_INPUT);
    EXPECT_EQ(buffer[0], '\0');
    EXPECT_EQ(buffer[1], 'x');

    std::memset(buffer, 'x', sizeof buffer);
    EXPECT_EQ(plugin().create(bad.c_str(), kSourceDir.c_str(), &s, buffer, 0), NENRIN_ERROR_INPUT);
    EXPECT_EQ(buffer[0], 'x');

    EXPECT_EQ(plugin().create(bad.c_str(), kSourceDir.c_str(), &s, nullptr, 100),
              NENRIN_ERROR_INPUT);
    EXPECT_EQ(s, nullptr);
}

TEST_F(ShaderPlugin, TruncationKeepsUtf8Whole) {
    // "wood-\u00fc.json: cannot open ...": 7 bytes would end inside the two-byte u-umlaut.
    const char* description = "{\"skeleton\": \"wood-\xc3\xbc.json\"}";
    nenrin_shader* s = nullptr;
    char buffer[16];
    EXPECT_EQ(plugin().create(description, nullptr, &s, buffer, 7), NENRIN_ERROR_INPUT);
    EXPECT_STREQ(buffer, "wood-");
    EXPECT_EQ(plugin().create(description, nullptr, &s, buffer, 8), NENRIN_ERROR_INPUT);
    EXPECT_STREQ(buffer, "wood-\xc3\xbc");
}

TEST_F(ShaderPlugin, DestroyingNullTouchesNoShader) {
    // Two live shaders; freeing NULL between evaluations changes neither's results.
    Created a = create(coniferDescription());
    Created b = create(coniferDescription());
    ASSERT_EQ(a.status, NENRIN_OK) << a.message;
    ASSERT_EQ(b.status, NENRIN_OK) << b.message;
    const Points points = crossSection(1.13f, 0.15f, 16);
    const std::vector<nenrin_shading_result> before = evaluate(a.shader.get(), points, nullptr);
    plugin().destroy(nullptr);
    b.shader.reset();  // a real destroy of the other one
    plugin().destroy(nullptr);
    const std::vector<nenrin_shading_result> after = evaluate(a.shader.get(), points, nullptr);
    ASSERT_EQ(after.size(), before.size());
    EXPECT_EQ(std::memcmp(after.data(), before.data(), before.size() * sizeof before[0]), 0);
}

// --- Threads.

TEST_F(ShaderPlugin, ConcurrentEvaluationEqualsSerial) {
    Created c = create(coniferDescription());
    ASSERT_EQ(c.status, NENRIN_OK) << c.message;
    const Points points = coniferSamples();
    const std::vector<float> footprints = footprintsFor(points);
    const std::vector<nenrin_shading_result> serial =
        evaluate(c.shader.get(), points, footprints.data());

    constexpr int kThreads = 2, kRounds = 4;
    std::array<std::vector<nenrin_shading_result>, kThreads * kRounds> results;
    std::array<nenrin_status, kThreads * kRounds> statuses;
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t)
        threads.emplace_back([&, t] {
            for (int r = 0; r < kRounds; ++r) {
                auto& out = results[t * kRounds + r];
                out.resize(serial.size());
                char message[256];
                statuses[t * kRounds + r] =
                    plugin().evaluate(c.shader.get(), out.size(), points.data(), footprints.data(),
                                      out.data(), message, sizeof message);
            }
        });
    for (std::thread& t : threads) t.join();
    for (size_t k = 0; k < results.size(); ++k) {
        EXPECT_EQ(statuses[k], NENRIN_OK);
        EXPECT_EQ(std::memcmp(results[k].data(), serial.data(),
                              serial.size() * sizeof(nenrin_shading_result)),
                  0)
            << "run " << k;
    }
}

TEST_F(ShaderPlugin, ConcurrentCreation) {
    std::array<Created, 2> created;
    std::vector<std::thread> threads;
    for (size_t t = 0; t < created.size(); ++t)
        threads.emplace_back([&, t] { created[t] = create(coniferDescription()); });
    for (std::thread& t : threads) t.join();
    const Points points = crossSection(2.27f, 0.1f, 8);
    for (const Created& c : created) ASSERT_EQ(c.status, NENRIN_OK) << c.message;
    std::vector<nenrin_shading_result> a = evaluate(created[0].shader.get(), points);
    std::vector<nenrin_shading_result> b = evaluate(created[1].shader.get(), points);
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof a[0]), 0);
}

// --- The library itself.

/// Runs a command, returns its standard output.
std::string run(const std::string& command) {
    std::string out;
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) return out;
    char buffer[4096];
    size_t n;
    while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) out.append(buffer, n);
    EXPECT_EQ(pclose(pipe), 0) << command;
    return out;
}

TEST(ShaderPluginLibrary, ExportsOnlyTheCAbi) {
    if (std::string(NENRIN_NM).empty()) GTEST_SKIP() << "no nm";
    std::istringstream symbols(
        run(std::string("'") + NENRIN_NM + "' -D --defined-only '" NENRIN_SHADER_PLUGIN "'"));
    std::vector<std::string> names;
    for (std::string line; std::getline(symbols, line);) {
        std::string name = line.substr(line.rfind(' ') + 1);
        EXPECT_EQ(name.rfind("nenrin_shader_", 0), 0u) << "exported: " << line;
        names.push_back(name);
    }
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"nenrin_shader_abi_version", "nenrin_shader_create",
                                               "nenrin_shader_destroy", "nenrin_shader_evaluate",
                                               "nenrin_shader_version"}));
}

TEST(ShaderPluginLibrary, NeedsNoRendererLibraries) {
    if (std::string(NENRIN_READELF).empty()) GTEST_SKIP() << "no readelf";
    std::string dynamic =
        run(std::string("'") + NENRIN_READELF + "' -d '" NENRIN_SHADER_PLUGIN "'");
    EXPECT_NE(dynamic.find("libembree3"), std::string::npos) << dynamic;
    for (const char* unwanted : {"OpenImageIO", "openvdb", "OpenColorIO", "OpenEXR", "Imath"})
        EXPECT_EQ(dynamic.find(unwanted), std::string::npos) << unwanted << "\n" << dynamic;
}

}  // namespace
}  // namespace nenrin
