/// The C ABI of the wood shader (include/nenrin/shader.h, docs/plugin.md): a JSON description
/// becomes a skeleton, its index, the growth field and a WoodShader behind an opaque handle;
/// evaluation forwards to WoodShader::evaluateSurface. No C++ exception crosses the ABI: every
/// entry point turns them into a status and a message.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <memory>
#include <mutex>
#include <new>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "grain/grain_params.h"
#include "grain/grown_tree.h"
#include "nenrin/shader.h"
#include "shader/finish.h"
#include "shader/wood_shader.h"
#include "skeleton/skeleton_file.h"
#include "util/input_error.h"
#include "util/json_reader.h"

#ifndef NENRIN_VERSION
#error "NENRIN_VERSION must be defined by the build"
#endif

namespace nenrin {

namespace {

/// Stands for the file in messages about the description itself.
constexpr const char* kDescriptionName = "<description>";

/// Points per call of evaluateSurface: bounds the scratch memory whatever the host's batch
/// size (results do not depend on the batching).
constexpr size_t kChunk = 4096;

/// Per-evaluation buffers, reused across calls through the pool below.
struct PluginScratch {
    WoodScratch wood;
    std::vector<Vec3> points;
    std::vector<SurfaceFootprint> footprints;
    std::vector<WoodSurfaceSample> samples;
};

/// A stack of scratch buffers: each call takes one and gives it back, so concurrent calls on
/// one shader never share buffers and sequential calls do not reallocate. (A thread_local
/// would pin the library in memory after dlclose while the host's threads live on.)
class ScratchPool {
public:
    std::unique_ptr<PluginScratch> take() {
        {
            std::lock_guard lock(mutex_);
            if (!free_.empty()) {
                std::unique_ptr<PluginScratch> s = std::move(free_.back());
                free_.pop_back();
                return s;
            }
        }
        return std::make_unique<PluginScratch>();
    }

    void give(std::unique_ptr<PluginScratch> s) noexcept {
        try {
            std::lock_guard lock(mutex_);
            free_.push_back(std::move(s));
        } catch (...) {
            // Out of memory for the pool slot: the buffers are simply freed.
        }
    }

private:
    std::mutex mutex_;
    std::vector<std::unique_ptr<PluginScratch>> free_;
};

/// Returns a scratch to its pool when the evaluation ends, however it ends.
class ScratchLease {
public:
    explicit ScratchLease(ScratchPool& pool) : pool_(pool), scratch_(pool.take()) {}
    ~ScratchLease() { pool_.give(std::move(scratch_)); }
    ScratchLease(const ScratchLease&) = delete;
    ScratchLease& operator=(const ScratchLease&) = delete;
    PluginScratch& operator*() { return *scratch_; }

private:
    ScratchPool& pool_;
    std::unique_ptr<PluginScratch> scratch_;
};

/// Copies the concatenation of `a` and `b` into the host's buffer: always NUL-terminated,
/// truncated to `size` bytes without splitting a UTF-8 sequence. Never throws or allocates, so
/// it is safe inside catch handlers (even for std::bad_alloc).
void writeMessage(char* buffer, size_t size, const char* a, const char* b = "") noexcept {
    if (!buffer || size == 0) return;
    const size_t la = std::strlen(a), lb = std::strlen(b), total = la + lb;
    auto at = [&](size_t i) { return i < la ? a[i] : b[i - la]; };
    size_t n = std::min(total, size - 1);
    if (n < total)
        while (n > 0 && (static_cast<unsigned char>(at(n)) & 0xC0) == 0x80) --n;
    for (size_t i = 0; i < n; ++i) buffer[i] = at(i);
    buffer[n] = '\0';
}

/// An error the caller made (as opposed to bad input text): NENRIN_ERROR_INVALID_ARGUMENT.
struct InvalidArgument : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// Runs `body`, mapping every exception to a status and the message to the host's buffer.
template <class Body>
nenrin_status guarded(char* message, size_t size, Body&& body) noexcept {
    try {
        body();
        writeMessage(message, size, "");
        return NENRIN_OK;
    } catch (const InvalidArgument& e) {
        writeMessage(message, size, e.what());
        return NENRIN_ERROR_INVALID_ARGUMENT;
    } catch (const InputError& e) {
        writeMessage(message, size, e.what());
        return NENRIN_ERROR_INPUT;
    } catch (const std::bad_alloc&) {
        writeMessage(message, size, "out of memory");
        return NENRIN_ERROR_INTERNAL;
    } catch (const std::exception& e) {
        writeMessage(message, size, "internal error: ", e.what());
        return NENRIN_ERROR_INTERNAL;
    } catch (...) {
        writeMessage(message, size, "internal error: unknown exception");
        return NENRIN_ERROR_INTERNAL;
    }
}

/// A "skeleton" or "grain" entry of the description: a file or an inline object.
struct Part {
    std::string file;                         ///< resolved file name, or empty
    const nlohmann::json* inlined = nullptr;  ///< the inline object, or null
};

Part readPart(JsonReader& r, const nlohmann::json& root, const std::string& key,
              const std::string& baseDirectory) {
    const nlohmann::json& v = root.at(key);
    if (v.is_object()) {
        r.object(key);  // marks the key as read; the parser checks the object itself
        return {"", &v};
    }
    if (!v.is_string())
        throw r.error(key, fmt::format("expected a file name or an inline {} object, found {}", key,
                                       jsonTypeName(v)));
    std::string name = r.string(key, "");
    if (name.empty()) throw r.error(key, "expected a file name, found an empty string");
    std::filesystem::path p(name);
    if (p.is_absolute() || baseDirectory.empty()) return {name, nullptr};
    return {(std::filesystem::path(baseDirectory) / p).lexically_normal().string(), nullptr};
}

/// Parses an inline object with `parse`, locating its errors inside the description
/// (`skeleton.trunk.points` rather than `trunk.points`).
template <class Parse>
auto parseInline(const nlohmann::json& node, const std::string& key, Parse&& parse) {
    try {
        return parse(node, kDescriptionName);
    } catch (const InputError& e) {
        const std::string& where = e.where();
        std::string located = where.empty() || where == "(top level)" ? key
                              : where.front() == '['                  ? key + where
                                                                      : key + "." + where;
        throw InputError(e.file(), located, e.message());
    }
}

}  // namespace

/// What the opaque handle holds. Built in place and never moved: the index points to the
/// skeleton, the field to the index, the shader to the field.
class PluginShader {
public:
    PluginShader(const std::string& description, const std::string& baseDirectory) {
        nlohmann::json json = parseJsonText(description, kDescriptionName);
        JsonReader r(json, kDescriptionName);
        if (!r.has("skeleton"))
            throw r.error("skeleton", "missing: a skeleton file name or an inline skeleton object");
        Part skeleton = readPart(r, json, "skeleton", baseDirectory);
        std::optional<Part> grain;
        if (r.has("grain")) grain = readPart(r, json, "grain", baseDirectory);
        const Finish finish = readFinish(r);
        // Every key of the description is checked before any file is read.
        r.finish();

        Skeleton tree = skeleton.inlined ? parseInline(*skeleton.inlined, "skeleton", parseSkeleton)
                                         : loadSkeletonFile(skeleton.file);
        GrainParams params;
        if (grain)
            params = grain->inlined ? parseInline(*grain->inlined, "grain", parseGrain)
                                    : loadGrainFile(grain->file);
        tree_ = std::make_unique<GrownTree>(std::move(tree), std::move(params));
        shader_ = std::make_unique<WoodShader>(tree_->field(), finish);
    }

    PluginShader(const PluginShader&) = delete;
    PluginShader& operator=(const PluginShader&) = delete;

    void evaluate(size_t count, const float* points, const float* footprints,
                  nenrin_shading_result* out) const {
        if (count == 0) return;
        if (!points) throw InvalidArgument("points is NULL");
        if (!out) throw InvalidArgument("out is NULL");
        if (count > SIZE_MAX / (3 * sizeof(float)))
            throw InvalidArgument(fmt::format("count {} is too large", count));
        // Everything is checked before anything is written.
        for (size_t i = 0; i < count; ++i) {
            const float* p = points + 3 * i;
            if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
                throw InvalidArgument(
                    fmt::format("point {} = ({}, {}, {}): expected finite x, y, z (metres)", i,
                                p[0], p[1], p[2]));
            if (footprints && !(std::isfinite(footprints[i]) && footprints[i] >= 0))
                throw InvalidArgument(
                    fmt::format("footprint {} = {}: expected a finite diameter >= 0 (metres)", i,
                                footprints[i]));
        }

        ScratchLease lease(pool_);
        PluginScratch& s = *lease;
        for (size_t begin = 0; begin < count; begin += kChunk) {
            const size_t n = std::min(kChunk, count - begin);
            s.points.resize(n);
            for (size_t i = 0; i < n; ++i) {
                const float* p = points + 3 * (begin + i);
                s.points[i] = {p[0], p[1], p[2]};
            }
            s.footprints.resize(footprints ? n : 0);
            for (size_t i = 0; i < s.footprints.size(); ++i)
                s.footprints[i] = {{}, {}, footprints[begin + i], {}};
            s.samples.resize(n);
            shader_->evaluateSurface(s.points, s.footprints, s.samples, s.wood);
            for (size_t i = 0; i < n; ++i)
                convert(s.samples[i], shader_->finish().surfaceRoughness(), out[begin + i]);
        }
    }

private:
    static void convert(const WoodSurfaceSample& w, double roughness, nenrin_shading_result& o) {
        // The ABI's albedo is black outside the felled log (the host draws its own bark).
        const Rgb albedo = w.coverage > 0 ? w.albedo : Rgb{};
        o.albedo[0] = static_cast<float>(albedo.r);
        o.albedo[1] = static_cast<float>(albedo.g);
        o.albedo[2] = static_cast<float>(albedo.b);
        o.roughness = static_cast<float>(roughness);
        o.fibre[0] = static_cast<float>(w.fibre.x);
        o.fibre[1] = static_cast<float>(w.fibre.y);
        o.fibre[2] = static_cast<float>(w.fibre.z);
        o.T = static_cast<float>(w.T);
        o.knot = static_cast<float>(w.knot);
        o.dead_knot = static_cast<float>(w.deadKnot);
        o.coverage = static_cast<float>(w.coverage);
        o.late_wood = static_cast<float>(w.lateWood);
    }

    std::unique_ptr<GrownTree> tree_;
    std::unique_ptr<WoodShader> shader_;
    /// Scratch is not part of the shader's state: evaluate() is const and thread-safe.
    mutable ScratchPool pool_;
};

}  // namespace nenrin

/// The C handle is the C++ object (the header only declares the name).
struct nenrin_shader : nenrin::PluginShader {
    using nenrin::PluginShader::PluginShader;
};

extern "C" {

int nenrin_shader_abi_version(void) { return NENRIN_SHADER_ABI_VERSION; }

const char* nenrin_shader_version(void) { return NENRIN_VERSION; }

nenrin_status nenrin_shader_create(const char* json_description, const char* base_directory,
                                   nenrin_shader** out, char* message, size_t message_size) {
    if (out) *out = nullptr;
    return nenrin::guarded(message, message_size, [&] {
        if (!json_description) throw nenrin::InvalidArgument("json_description is NULL");
        if (!out) throw nenrin::InvalidArgument("out is NULL");
        *out = new nenrin_shader(json_description, base_directory ? base_directory : "");
    });
}

nenrin_status nenrin_shader_evaluate(const nenrin_shader* shader, size_t count, const float* points,
                                     const float* footprints, nenrin_shading_result* out,
                                     char* message, size_t message_size) {
    return nenrin::guarded(message, message_size, [&] {
        if (!shader) throw nenrin::InvalidArgument("shader is NULL");
        shader->evaluate(count, points, footprints, out);
    });
}

void nenrin_shader_destroy(nenrin_shader* shader) { delete shader; }

}  // extern "C"
