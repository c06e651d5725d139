#pragma once
/// Triangle meshes from Wavefront OBJ files (read with tinyobjloader): positions with optional
/// normals and uvs, unified so that every triangle corner is one index into all three arrays.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "util/vec3.h"

namespace nenrin {

/// A triangle mesh with one index per corner into unified vertex arrays (an OBJ corner whose
/// position/normal/uv indices differ becomes its own vertex). Units as in the file (metres).
struct TriangleMesh {
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;  ///< per vertex, unit length; empty if the file has none
    std::vector<std::array<double, 2>> uvs;  ///< per vertex; empty if the file has none
    std::vector<std::array<uint32_t, 3>> triangles;
    /// Per triangle, the loaders' labels: its group (an OBJ object or group, a glTF node's
    /// primitive) and its material, indices into the name lists. Empty when not known.
    std::vector<uint32_t> triangleGroups, triangleMaterials;
    std::vector<std::string> groupNames, materialNames;
};

/// Loads a Wavefront OBJ (all objects/groups merged, polygons triangulated). Throws InputError
/// (util/input_error.h: file, where, message) for a missing/unreadable file, a parse error
/// (with the line when tinyobjloader reports it), no triangles, non-finite coordinates,
/// indices out of range, or a mix of corners with and without normals/uvs (then say which
/// triangle / line). Warnings from tinyobjloader about missing .mtl files are ignored.
///
/// Details: `where` is "line N" (the OBJ line, counted like tinyobjloader: \n, \r\n or \r end a
/// line). Vertices are numbered in the order their (v, vt, vn) triple first appears, so the
/// same file always gives the same arrays. Polygons keep their winding; a quad is split along
/// its shorter diagonal, larger (also concave) polygons by ear clipping in their plane.
/// Zero-area triangles are kept. Each triangle is labelled with its object/group (`o`/`g`: the
/// name tinyobjloader gives its shape; "" before any) and its `usemtl` material name ("" before
/// any); .mtl files are not read. Smoothing groups, lines (`l`) and points (`p`) are ignored.
/// Coordinates pass through tinyobjloader's single-precision floats.
TriangleMesh loadObjMesh(const std::string& path);

/// Axis-aligned bounds of the positions (an empty mesh gives lower = +inf, upper = -inf).
void meshBounds(const TriangleMesh& mesh, Vec3& lower, Vec3& upper);

/// Area-weighted normals per vertex when the file has none (for smooth shading), unit length.
/// Never NaN: a vertex whose weighted sum vanishes (only zero-area triangles, or faces that
/// cancel) takes the normal of its first non-degenerate triangle, else (0, 0, 1). Vertices split
/// at uv seams are separate vertices and are not averaged with each other.
std::vector<Vec3> computeVertexNormals(const TriangleMesh& mesh);

}  // namespace nenrin
