#pragma once
/// Light environment of Kanayama et al. (after Chiba et al.): every new shoot's leaves form a
/// leaf sphere; a huge sky dome lights the tree; a sphere's light is the dome's light after all
/// other spheres have been projected onto the dome and dimmed it.
///
/// The dome is a fixed set of K stratified directions over the upper hemisphere, weighted by
/// the CIE standard overcast sky (luminance ~ 1 + 2 sin(elevation)); weights sum to 1, so an
/// open-sky sphere receives L = brightness. A sphere dims a direction by Beer-Lambert over the
/// chord the ray from the receiving sphere's centre cuts through it: T = exp(-k * chord).
/// Chords are summed as integers (units of 1e-7 m), so the result does not depend on the order
/// in which spheres are visited: the Embree tracer and the O(n^2) reference give the same light
/// bit for bit, with any number of threads.

#include <cstdint>
#include <memory>
#include <vector>

#include "util/vec3.h"

namespace nenrin {

struct LeafSphere {
    Vec3 center;
    double radius = 0;  ///< m
};

struct SkyDome {
    std::vector<Vec3> directions;  ///< unit, z > 0
    std::vector<double> weights;   ///< sum to 1
};

/// K directions stratified in (azimuth, sin(elevation)) cells of equal solid angle, jittered
/// by a fixed seed (the same dome for every tree), weighted by the CIE overcast luminance.
SkyDome makeSkyDome(int directionCount);

struct LeafLightParameters {
    double extinction = 12;  ///< 1/m inside a leaf sphere
    double brightness = 1;   ///< sky brightness: scales every sphere's light
    int threads = 0;         ///< 0 = all worker threads
    /// Embree: 16-ray packets (rtcOccluded16) instead of single rays (rtcOccluded1). The rays
    /// of one sphere share an origin but fan out over the dome, so packets lose (~2x slower).
    bool packets = false;
};

struct SphereLight {
    double light = 0;                  ///< received light, brightness for an open sky
    Vec3 brightestDirection{0, 0, 1};  ///< light-weighted mean of the transmitted directions
};

/// The paper's method: for each sphere, project every other sphere onto the dome. O(n^2 K).
std::vector<SphereLight> leafLightReference(const std::vector<LeafSphere>& spheres,
                                            const SkyDome& dome, const LeafLightParameters& p);

/// Embree occlusion rays (spheres as user geometry, every hit accumulated in the occlusion
/// callback, rays end early once a direction is dark): O(n K (log n + hits per ray)). Holds an
/// Embree device; one per simulation.
class LeafLightTracer {
public:
    LeafLightTracer();
    ~LeafLightTracer();
    LeafLightTracer(const LeafLightTracer&) = delete;
    LeafLightTracer& operator=(const LeafLightTracer&) = delete;

    std::vector<SphereLight> compute(const std::vector<LeafSphere>& spheres, const SkyDome& dome,
                                     const LeafLightParameters& p) const;

private:
    struct Device;
    std::unique_ptr<Device> device_;
};

}  // namespace nenrin
