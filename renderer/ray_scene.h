#pragma once
/// The scene's geometry in an Embree BVH: boxes and meshes as triangles in world space (one
/// box per glued block; the lamella is found from the hit point later), rectangle lights as
/// two emitting triangles. Embree stays behind this file (pimpl).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <type_traits>

#include "renderer/camera.h"
#include "renderer/scene.h"

namespace nenrin {

struct SurfaceHit {
    bool hit = false;
    double distance = 0;
    Vec3 position;
    Vec3 geometricNormal;  ///< unit, world space, as wound (not flipped towards the ray)
    Vec3 shadingNormal;    ///< unit; interpolated vertex normals of meshes that have them
    double u = 0, v = 0;   ///< texture coordinates (meshes with uvs), else 0
    Vec3 dpdu, dpdv;       ///< world-space derivatives of position over u and v (meshes with uvs)
    bool isLight = false;  ///< a rectangle light was hit
    uint32_t index = 0;    ///< scene object index, or light index if isLight
};

/// Ray origin nudged off the surface at p along its geometric normal ng, to the side of
/// `towards`: a ray leaving the surface does not find it again through rounding.
inline Vec3 offsetOrigin(const Vec3& p, const Vec3& ng, const Vec3& towards) {
    double scale = 1e-5 * (1 + std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}));
    return p + ng * (dot(ng, towards) > 0 ? scale : -scale);
}

/// Elements `stride` bytes apart: one field of each element of an array of structs, read or
/// written where it lies (packets of rays go to and from paths without copies).
template <class T>
class Strided {
public:
    Strided(T* first, size_t stride = sizeof(T)) : first_(first), stride_(stride) {}
    T& operator[](size_t i) const {
        using Byte = std::conditional_t<std::is_const_v<T>, const char, char>;
        return *reinterpret_cast<T*>(reinterpret_cast<Byte*>(first_) + i * stride_);
    }

private:
    T* first_;
    size_t stride_;
};

class RayScene {
public:
    explicit RayScene(const Scene& scene);
    ~RayScene();
    RayScene(const RayScene&) = delete;
    RayScene& operator=(const RayScene&) = delete;

    SurfaceHit intersect(const Ray& ray) const;
    /// Up to 16 coherent rays at once (Embree packets: ~3x faster for camera rays).
    void intersect16(Strided<const Ray> rays, int count, Strided<SurfaceHit> hits) const;
    /// True if anything lies on the ray between 0 and tMax.
    bool occluded(const Ray& ray, double tMax) const;
    /// Up to 16 shadow rays at once (Embree packets; shadow rays of neighbouring samples
    /// towards one light are coherent). occluded[i] answers ray i.
    void occluded16(Strided<const Ray> rays, Strided<const double> tMax, int count,
                    Strided<bool> occluded) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace nenrin
