#include "renderer/material_bsdf.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace nenrin {

namespace {

/// Wood: the evaluated wood under the finish, tinted by the board's tree and blended with the
/// glue line; the late-wood relief bumps the normal. Returns the world-space fibre direction.
Vec3 woodLayers(const Material& material, const MaterialHit& at, SurfaceBsdf& bsdf, Vec3& ns) {
    const WoodSurfaceSample& wood = *at.wood;
    const Finish& finish = material.wood->finish();
    if (wood.coverage > 0) {
        bsdf.base = multiply(wood.albedo, at.boardTint);
        bsdf.fibreStrength = finish.fibreStrength;
        bsdf.fibreWidth = finish.fibreWidth;
    } else {
        // Past the felled log's wood: the shader's bark where it drew one (camera hits), the
        // plain bark colour otherwise.
        bsdf.base = wood.albedo == Rgb{} ? kBarkAlbedo : wood.albedo;
    }
    if (at.glue && at.glueCover > 0) {
        const double* g = at.glue->colour;
        bsdf.base = mix(bsdf.base, Rgb{g[0], g[1], g[2]}, at.glueCover);
        bsdf.fibreStrength *= 1 - at.glueCover;
    }
    bsdf.coatWeight = finish.coatWeight;
    bsdf.coatAlpha = std::max(finish.coatRoughness, at.minRoughness);
    bsdf.ior = finish.coatIor;
    // Relief: tilt the normal against the height gradient's part along the surface.
    Vec3 g = wood.reliefGradient;
    Vec3 bumped = normalize(ns - (g - ns * dot(g, ns)));
    if (dot(bumped, at.wo) > 0) ns = bumped;
    return wood.fibre;
}

/// Baked wood maps: the same layered surface, its inputs read from the textures in the tangent
/// frame of the uv layout (tangent +u, bitangent +v). Returns the world-space fibre direction
/// (zero without a fibre map).
Vec3 texturedLayers(const Material& material, const MaterialHit& at, SurfaceBsdf& bsdf, Vec3& ns) {
    const SurfaceHit& hit = *at.hit;
    const Finish& finish = material.finish;
    Vec3 c = material.baseColourMap->lookup3(hit.u, hit.v);
    bsdf.base = {c.x, c.y, c.z};
    bsdf.coatWeight = finish.coatWeight;
    bsdf.coatAlpha = std::max(finish.coatRoughness, at.minRoughness);
    bsdf.ior = finish.coatIor;
    // The frame the maps were baked in: the normal before the normal map bumps it (the
    // fibre is a direction in the wood, not tilted by the relief).
    const Vec3 normal = ns;
    Vec3 tangent = normalize(hit.dpdu - normal * dot(normal, hit.dpdu));
    Vec3 bitangent = cross(normal, tangent);
    if (dot(bitangent, hit.dpdv) < 0) bitangent = -bitangent;
    auto fromTangentSpace = [&](const ImageTexture& map) {
        Vec3 e = map.lookup3(hit.u, hit.v) * 2 - Vec3{1, 1, 1};
        return tangent * e.x + bitangent * e.y + normal * e.z;
    };
    Vec3 fibre;
    if (lengthSquared(tangent) > 0) {
        if (material.normalMap) {
            Vec3 bumped = normalize(fromTangentSpace(*material.normalMap));
            if (dot(bumped, at.wo) > 0) ns = bumped;
        }
        if (material.fibreMap) fibre = normalize(fromTangentSpace(*material.fibreMap));
        if (material.anisotropyMap) {
            // glTF's lobe direction lies across the fibres, in RG; B is 1 - the fibre's angle
            // out of the surface / 90 degrees (renderer/texture_set/gltf_model.h): the fibre
            // is the direction turned back by 90 degrees about the normal and tilted out of
            // the surface by that angle.
            const Vec3 a = material.anisotropyMap->lookup3(hit.u, hit.v);
            const double ax = 2 * a.x - 1, ay = 2 * a.y - 1, h = std::hypot(ax, ay);
            const double dive = (1 - std::clamp(double(a.z), 0.0, 1.0)) * 0.5 * std::numbers::pi;
            if (h > 1e-6)
                fibre = normalize((tangent * (ay / h) - bitangent * (ax / h)) * std::cos(dive) +
                                  normal * std::sin(dive));
        }
        if (lengthSquared(fibre) > 0) {
            bsdf.fibreStrength = finish.fibreStrength;
            bsdf.fibreWidth = finish.fibreWidth;
        }
    }
    return fibre;
}

/// Diffuse, glossy (a coat over the base) and metal.
void plainLayers(const Material& material, const MaterialHit& at, SurfaceBsdf& bsdf) {
    bsdf.base = material.colour;
    if (material.type == MaterialType::Glossy) {
        bsdf.coatWeight = 1;
        bsdf.coatAlpha = std::max(material.roughness, at.minRoughness);
    } else if (material.type == MaterialType::Metal) {
        bsdf.metal = true;
        bsdf.metalF0 = material.colour;
        bsdf.metalAlpha = std::max(material.roughness, at.minRoughness);
    }
}

}  // namespace

SurfaceShading materialBsdf(const Material& material, const MaterialHit& at) {
    SurfaceShading s;
    s.ns = at.ns;
    Vec3 fibre;  ///< world space; zero = no fibre lobe
    if (material.type == MaterialType::Wood)
        fibre = woodLayers(material, at, s.bsdf, s.ns);
    else if (material.type == MaterialType::Textured)
        fibre = texturedLayers(material, at, s.bsdf, s.ns);
    else
        plainLayers(material, at, s.bsdf);
    s.frame = AxisFrame(s.ns);
    if (lengthSquared(fibre) > 0) s.bsdf.fibre = s.frame.toLocal(fibre);
    return s;
}

}  // namespace nenrin
