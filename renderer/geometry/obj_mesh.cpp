#include "renderer/geometry/obj_mesh.h"

#include <fmt/format.h>
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cfloat>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <numeric>
#include <regex>
#include <sstream>
#include <string_view>

#include "util/input_error.h"
#include "util/input_file.h"

namespace nenrin {

namespace {

// About 15 million triangles; tinyobjloader holds the text and its parse at once.
constexpr uintmax_t kMaxObjFileBytes = uintmax_t(1) << 30;

/// Polygons with up to this many corners get the best ear (shortest new edge) at every step,
/// O(n³); larger ones the first ear found, so a 1000-gon does not take seconds.
constexpr size_t kBestEarCorners = 16;

/// One `f` line as the pre-scan saw it.
struct FaceLine {
    size_t line;
    uint32_t corners;
    uint32_t material;  ///< index into the scan's material names
};

bool isBlank(char c) { return c == ' ' || c == '\t'; }

std::vector<std::string_view> splitAtBlanks(std::string_view s) {
    std::vector<std::string_view> out;
    size_t i = 0;
    while (i < s.size()) {
        while (i < s.size() && isBlank(s[i])) ++i;
        size_t start = i;
        while (i < s.size() && !isBlank(s[i])) ++i;
        if (i > start) out.push_back(s.substr(start, i - start));
    }
    return out;
}

/// Calls f(lineNumber, line) per line, split like tinyobjloader's safeGetline (\n, \r\n or a
/// lone \r end a line) so that our line numbers match its messages.
template <class F>
void forEachLine(std::string_view text, F&& f) {
    size_t line = 0, i = 0;
    while (i < text.size()) {
        size_t end = std::min(text.find_first_of("\r\n", i), text.size());
        f(++line, text.substr(i, end - i));
        if (end + 1 < text.size() && text[end] == '\r' && text[end + 1] == '\n') ++end;
        i = end + 1;
    }
}

size_t lineOfOffset(std::string_view text, size_t offset) {
    size_t line = 0;
    forEachLine(text.substr(0, offset + 1), [&](size_t n, std::string_view) { line = n; });
    return line;
}

/// The checks tinyobjloader does not make: it reads an unparseable number (`nan`, `1,5`) as 0,
/// drops faces it cannot use with at most a warning, and keeps no line numbers. The scan
/// mirrors its line and keyword rules, throws for what it would let through, and records each
/// face's line for the checks that need tinyobjloader's result.
class Scanner {
public:
    explicit Scanner(const std::string& file) : file_(file) {}

    std::vector<FaceLine> scan(std::string_view text) {
        forEachLine(text, [&](size_t line, std::string_view s) {
            line_ = line;
            size_t start = s.find_first_not_of(" \t");
            if (start == std::string_view::npos) return;
            s.remove_prefix(start);
            auto is = [&](std::string_view keyword) {
                return s.size() > keyword.size() && s.substr(0, keyword.size()) == keyword &&
                       isBlank(s[keyword.size()]);
            };
            if (is("v")) {
                numbers(s.substr(2), "v", 3);
                ++positions_;
            } else if (is("vn")) {
                numbers(s.substr(3), "vn", 3);
                ++normals_;
            } else if (is("vt")) {
                numbers(s.substr(3), "vt", 1);
                ++uvs_;
            } else if (is("f")) {
                face(s.substr(2));
            } else if (is("usemtl")) {
                useMaterial(s.substr(7));
            }
        });
        return std::move(faces_);
    }

    /// The `usemtl` names in first-use order ("" for faces before any).
    const std::vector<std::string>& materials() const { return materialNames_; }

private:
    InputError error(const std::string& message) const {
        return InputError(file_, fmt::format("line {}", line_), message);
    }

    void numbers(std::string_view rest, const char* keyword, size_t minimum) {
        // tinyobjloader ignores what follows the numbers, so a trailing comment is fine.
        auto tokens = splitAtBlanks(rest.substr(0, rest.find('#')));
        if (tokens.size() < minimum)
            throw error(fmt::format("expected at least {} numbers after \"{}\", found {}", minimum,
                                    keyword, tokens.size()));
        for (std::string_view t : tokens) {
            std::string_view digits = t;
            if (digits.size() > 1 && digits[0] == '+' && digits[1] != '-') digits.remove_prefix(1);
            double value = 0;
            auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
            if (ec == std::errc::result_out_of_range)
                throw error(fmt::format("{} is out of range: expected a finite number", t));
            if (ec != std::errc() || end != digits.data() + digits.size())
                throw error(fmt::format("\"{}\" is not a number", t));
            if (!std::isfinite(value))
                throw error(fmt::format("expected finite coordinates, found {}", t));
            // tinyobjloader stores floats: anything larger would become infinite.
            if (std::abs(value) > FLT_MAX)
                throw error(
                    fmt::format("{} is out of range: expected |x| <= {:g} (tinyobjloader "
                                "reads single precision)",
                                t, FLT_MAX));
        }
    }

    void face(std::string_view rest) {
        auto corners = splitAtBlanks(rest);
        if (corners.size() < 3)
            throw error(fmt::format("a face needs at least 3 corners, found {}", corners.size()));
        for (size_t k = 0; k < corners.size(); ++k) corner(corners[k], k + 1);
        faces_.push_back({line_, static_cast<uint32_t>(corners.size()), material_});
    }

    void useMaterial(std::string_view rest) {
        const auto tokens = splitAtBlanks(rest.substr(0, rest.find('#')));
        const std::string name = tokens.empty() ? "" : std::string(tokens[0]);
        auto it = std::find(materialNames_.begin(), materialNames_.end(), name);
        material_ = static_cast<uint32_t>(it - materialNames_.begin());
        if (it == materialNames_.end()) materialNames_.push_back(name);
    }

    void corner(std::string_view token, size_t k) {
        std::vector<std::string_view> parts;
        for (size_t start = 0;;) {
            size_t slash = token.find('/', start);
            parts.push_back(token.substr(start, slash - start));
            if (slash == std::string_view::npos) break;
            start = slash + 1;
        }
        std::string_view v = parts[0];
        std::string_view vt = parts.size() > 1 ? parts[1] : std::string_view{};
        std::string_view vn = parts.size() > 2 ? parts[2] : std::string_view{};
        bool wellFormed = parts.size() <= 3 && !v.empty() && (parts.size() != 2 || !vt.empty()) &&
                          (parts.size() != 3 || !vn.empty());
        if (!wellFormed || !index(v, positions_, token, k, "vertex", "v") ||
            (!vt.empty() && !index(vt, uvs_, token, k, "uv", "vt")) ||
            (!vn.empty() && !index(vn, normals_, token, k, "normal", "vn")))
            throw error(
                fmt::format("corner {} \"{}\": expected v, v/vt, v//vn or v/vt/vn with "
                            "non-zero integer indices",
                            k, token));

        // One index per corner into one set of arrays: either every corner has a normal (uv)
        // or none has.
        bool hasUv = !vt.empty(), hasNormal = !vn.empty();
        if (firstFaceLine_ == 0) {
            firstFaceLine_ = line_;
            hasUv_ = hasUv;
            hasNormal_ = hasNormal;
        }
        auto mixed = [&](bool has, const char* what, const char* keyword) {
            return error(
                fmt::format("corner {} \"{}\" has {} {} index ({}) while the first face "
                            "(line {}) has {}: expected {}s on every corner or on none",
                            k, token, has ? "a" : "no", what, keyword, firstFaceLine_,
                            has ? "none" : "them", what));
        };
        if (hasNormal != hasNormal_) throw mixed(hasNormal, "normal", "vn");
        if (hasUv != hasUv_) throw mixed(hasUv, "uv", "vt");
    }

    /// False for a malformed or zero index. Positive indices may refer to elements defined
    /// further down (tinyobjloader resolves them at the end; loadObjMesh checks them);
    /// negative ones count back from the elements defined so far.
    bool index(std::string_view s, size_t definedSoFar, std::string_view token, size_t k,
               const char* what, const char* keyword) const {
        if (s.size() > 1 && s[0] == '+' && s[1] != '-') s.remove_prefix(1);
        int value = 0;
        auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
        if (ec != std::errc() || end != s.data() + s.size() || value == 0) return false;
        if (value < 0 && static_cast<size_t>(-static_cast<int64_t>(value)) > definedSoFar)
            throw error(
                fmt::format("corner {} \"{}\": relative {} index {} reaches before the "
                            "first \"{}\" line ({} so far)",
                            k, token, what, value, keyword, definedSoFar));
        return true;
    }

    const std::string& file_;
    size_t line_ = 0;
    size_t positions_ = 0, normals_ = 0, uvs_ = 0;
    size_t firstFaceLine_ = 0;
    bool hasUv_ = false, hasNormal_ = false;
    std::vector<FaceLine> faces_;
    std::vector<std::string> materialNames_{""};
    uint32_t material_ = 0;
};

std::string readText(const std::string& path) {
    std::string text = readInputFile(path, kMaxObjFileBytes, "an OBJ file");
    // tinyobjloader would stop reading a line at a NUL: this is not a text file.
    if (size_t nul = text.find('\0'); nul != std::string::npos)
        throw InputError(path, fmt::format("line {}", lineOfOffset(text, nul)),
                         "found a NUL byte: expected a text OBJ file");
    return text;
}

double cross2(const std::array<double, 2>& o, const std::array<double, 2>& a,
              const std::array<double, 2>& b) {
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

/// Appends the triangles of one polygon (vertex ids in corner order), keeping its winding.
/// Larger polygons are ear-clipped in their plane (Newell's normal, so concave and slightly
/// non-planar ones work), preferring the ear with the shortest new edge: a quad is split along
/// its shorter diagonal. A polygon without a plane, or one that leaves no ear (it crosses
/// itself), is finished as a fan; its zero-area triangles are kept like any others.
void triangulate(const std::vector<uint32_t>& poly, const std::vector<Vec3>& positions,
                 std::vector<std::array<uint32_t, 3>>& out) {
    const size_t n = poly.size();
    if (n == 3) {
        out.push_back({poly[0], poly[1], poly[2]});
        return;
    }
    std::vector<size_t> left(n);
    std::iota(left.begin(), left.end(), 0);
    auto fan = [&] {
        for (size_t i = 1; i + 1 < left.size(); ++i)
            out.push_back({poly[left[0]], poly[left[i]], poly[left[i + 1]]});
    };
    Vec3 normal;
    for (size_t i = 0; i < n; ++i) {
        const Vec3& a = positions[poly[i]];
        const Vec3& b = positions[poly[(i + 1) % n]];
        normal += {(a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y)};
    }
    normal = normalize(normal);
    if (normal == Vec3{} || !isFinite(normal)) return fan();

    // Seen from the tip of Newell's normal the polygon runs counter-clockwise in (u, v).
    Vec3 u = anyPerpendicular(normal), v = cross(normal, u);
    std::vector<std::array<double, 2>> p(n);
    for (size_t i = 0; i < n; ++i) p[i] = {dot(positions[poly[i]], u), dot(positions[poly[i]], v)};

    auto isEar = [&](size_t a, size_t b, size_t c) {
        if (cross2(p[a], p[b], p[c]) <= 0) return false;  // reflex or flat corner
        for (size_t q : left) {
            if (q == a || q == b || q == c || p[q] == p[a] || p[q] == p[b] || p[q] == p[c])
                continue;
            if (cross2(p[a], p[b], p[q]) >= 0 && cross2(p[b], p[c], p[q]) >= 0 &&
                cross2(p[c], p[a], p[q]) >= 0)
                return false;
        }
        return true;
    };
    while (left.size() > 3) {
        const size_t m = left.size();
        size_t best = m;
        double bestLength = std::numeric_limits<double>::infinity();
        for (size_t i = 0; i < m; ++i) {
            size_t a = left[(i + m - 1) % m], b = left[i], c = left[(i + 1) % m];
            if (!isEar(a, b, c)) continue;
            double dx = p[c][0] - p[a][0], dy = p[c][1] - p[a][1];
            if (dx * dx + dy * dy < bestLength) {
                best = i;
                bestLength = dx * dx + dy * dy;
            }
            if (m > kBestEarCorners) break;
        }
        if (best == m) break;
        out.push_back(
            {poly[left[(best + m - 1) % m]], poly[left[best]], poly[left[(best + 1) % m]]});
        left.erase(left.begin() + static_cast<std::ptrdiff_t>(best));
    }
    fan();
}

}  // namespace

namespace {

/// What tinyobjloader reads of the file, checked against the scan's face count.
struct ObjContent {
    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
};

ObjContent parseObj(const std::string& path, const std::string& text,
                    const std::vector<FaceLine>& faces) {
    ObjContent obj;
    std::vector<tinyobj::material_t> materials;
    std::string warnings, errors;
    std::istringstream stream(text);
    // No material reader: `mtllib` lines are skipped, no .mtl file is looked for. No
    // triangulation: tinyobjloader's drops a quad with a bad index with only a warning, and
    // ours knows each face's line. Its other warnings are all covered by our checks.
    bool parsed = tinyobj::LoadObj(&obj.attrib, &obj.shapes, &materials, &warnings, &errors,
                                   &stream, /*readMatFn=*/nullptr, /*triangulate=*/false,
                                   /*default_vcols_fallback=*/false);
    if (!parsed) {
        std::string message = oneLine(errors.empty() ? "unknown error" : errors);
        std::smatch m;
        std::string where;
        if (std::regex_search(message, m, std::regex(R"(line:? (\d+))")))
            where = "line " + m[1].str();
        throw InputError(path, where, "tinyobjloader cannot parse the file: " + message);
    }
    if (faces.empty())
        throw InputError(path, "",
                         "no faces: expected at least one triangle or polygon (\"f\" lines)");
    size_t faceCount = 0;
    for (const auto& shape : obj.shapes) faceCount += shape.mesh.num_face_vertices.size();
    if (faceCount != faces.size())
        throw InputError(path, "",
                         fmt::format("tinyobjloader read {} faces where the file has {} \"f\" "
                                     "lines: unsupported OBJ content",
                                     faceCount, faces.size()));
    return obj;
}

/// The mesh's vertices: one per distinct (v, vn, vt) corner, in first-seen order.
class VertexTable {
public:
    VertexTable(const std::string& path, const tinyobj::attrib_t& attrib, TriangleMesh& mesh)
        : path_(path), attrib_(attrib), mesh_(mesh) {}

    /// The vertex of corner k (1-based in messages) of the face at `where`.
    uint32_t vertexOf(const tinyobj::index_t& c, size_t k, const std::string& where) {
        checkIndex(c.vertex_index, attrib_.vertices.size() / 3, "vertex", "v", k, where);
        if (c.normal_index >= 0)
            checkIndex(c.normal_index, attrib_.normals.size() / 3, "normal", "vn", k, where);
        if (c.texcoord_index >= 0)
            checkIndex(c.texcoord_index, attrib_.texcoords.size() / 2, "uv", "vt", k, where);
        auto [it, isNew] = ids_.try_emplace({c.vertex_index, c.normal_index, c.texcoord_index},
                                            static_cast<uint32_t>(mesh_.positions.size()));
        if (isNew) add(c, k, where);
        return it->second;
    }

private:
    void checkIndex(int i, size_t count, const char* what, const char* keyword, size_t k,
                    const std::string& where) const {
        if (i >= 0 && static_cast<size_t>(i) < count) return;
        throw InputError(path_, where,
                         fmt::format("corner {}: {} index {} is out of range: the "
                                     "file has {} \"{}\" line{}",
                                     k + 1, what, i + 1, count, keyword, count == 1 ? "" : "s"));
    }

    void add(const tinyobj::index_t& c, size_t k, const std::string& where) {
        if (mesh_.positions.size() == std::numeric_limits<uint32_t>::max())
            throw InputError(path_, where, "too many vertices for 32-bit indices");
        const tinyobj::real_t* pv = &attrib_.vertices[3 * size_t(c.vertex_index)];
        mesh_.positions.push_back({pv[0], pv[1], pv[2]});
        // The scan bounds every number; this guards tinyobjloader's own rounding.
        if (!isFinite(mesh_.positions.back()))
            throw InputError(
                path_, where,
                fmt::format("corner {}: vertex {} is not finite", k + 1, c.vertex_index + 1));
        if (c.normal_index >= 0) {
            const tinyobj::real_t* nv = &attrib_.normals[3 * size_t(c.normal_index)];
            Vec3 normal = normalize(Vec3{nv[0], nv[1], nv[2]});
            if (normal == Vec3{} || !isFinite(normal))
                throw InputError(path_, where,
                                 fmt::format("corner {}: normal {} (\"vn\") has zero "
                                             "length: expected a direction",
                                             k + 1, c.normal_index + 1));
            mesh_.normals.push_back(normal);
        }
        if (c.texcoord_index >= 0) {
            const tinyobj::real_t* tv = &attrib_.texcoords[2 * size_t(c.texcoord_index)];
            mesh_.uvs.push_back({tv[0], tv[1]});
        }
    }

    const std::string& path_;
    const tinyobj::attrib_t& attrib_;
    TriangleMesh& mesh_;
    std::map<std::array<int, 3>, uint32_t> ids_;
};

}  // namespace

TriangleMesh loadObjMesh(const std::string& path) {
    const std::string text = readText(path);
    Scanner scanner(path);
    const std::vector<FaceLine> faces = scanner.scan(text);
    const ObjContent obj = parseObj(path, text, faces);
    TriangleMesh mesh;
    mesh.materialNames = scanner.materials();
    VertexTable vertices(path, obj.attrib, mesh);
    std::vector<uint32_t> polygon;
    size_t face = 0;
    for (const auto& shape : obj.shapes) {
        auto group = std::find(mesh.groupNames.begin(), mesh.groupNames.end(), shape.name);
        const auto groupId = static_cast<uint32_t>(group - mesh.groupNames.begin());
        if (group == mesh.groupNames.end()) mesh.groupNames.push_back(shape.name);
        size_t offset = 0;
        for (size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f, ++face) {
            const std::string where = fmt::format("line {}", faces[face].line);
            // num_face_vertices is an unsigned char: the scan's count is the true one.
            const size_t corners = faces[face].corners;
            if (static_cast<unsigned char>(corners) != shape.mesh.num_face_vertices[f] ||
                offset + corners > shape.mesh.indices.size())
                throw InputError(path, where,
                                 "tinyobjloader read this face differently: unsupported OBJ "
                                 "content");
            polygon.clear();
            for (size_t k = 0; k < corners; ++k)
                polygon.push_back(vertices.vertexOf(shape.mesh.indices[offset + k], k, where));
            offset += corners;
            triangulate(polygon, mesh.positions, mesh.triangles);
            mesh.triangleGroups.resize(mesh.triangles.size(), groupId);
            mesh.triangleMaterials.resize(mesh.triangles.size(), faces[face].material);
        }
    }
    return mesh;
}

void meshBounds(const TriangleMesh& mesh, Vec3& lower, Vec3& upper) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    lower = {inf, inf, inf};
    upper = -lower;
    for (const Vec3& p : mesh.positions) {
        lower = {std::min(lower.x, p.x), std::min(lower.y, p.y), std::min(lower.z, p.z)};
        upper = {std::max(upper.x, p.x), std::max(upper.y, p.y), std::max(upper.z, p.z)};
    }
}

std::vector<Vec3> computeVertexNormals(const TriangleMesh& mesh) {
    std::vector<Vec3> sum(mesh.positions.size()), firstFace(mesh.positions.size());
    for (const auto& t : mesh.triangles) {
        const Vec3& a = mesh.positions[t[0]];
        // |cross| is twice the triangle's area: summing it weights by area.
        Vec3 n = cross(mesh.positions[t[1]] - a, mesh.positions[t[2]] - a);
        Vec3 unit = normalize(n);
        bool usable = unit != Vec3{} && isFinite(unit);
        for (uint32_t i : t) {
            sum[i] += n;
            if (usable && firstFace[i] == Vec3{}) firstFace[i] = unit;
        }
    }
    std::vector<Vec3> normals(mesh.positions.size());
    for (size_t i = 0; i < normals.size(); ++i) {
        Vec3 n = normalize(sum[i]);
        if (n == Vec3{} || !isFinite(n)) n = firstFace[i] != Vec3{} ? firstFace[i] : Vec3{0, 0, 1};
        normals[i] = n;
    }
    return normals;
}

}  // namespace nenrin
