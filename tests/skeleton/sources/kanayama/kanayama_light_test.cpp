// Kanayama light environment: Embree tracer vs the O(n^2) projection reference, shading.
#include "skeleton/sources/kanayama/kanayama_light.h"

#include <gtest/gtest.h>

#include <cmath>

#include "util/hash.h"

namespace nenrin {
namespace {

std::vector<LeafSphere> randomCrown(uint64_t seed, int n) {
    std::vector<LeafSphere> spheres;
    for (int i = 0; i < n; ++i) {
        // A crown-like ellipsoidal cloud, 2 m wide, 3 m tall.
        Vec3 c{uniform01(seed, i, 0) * 2 - 1, uniform01(seed, i, 1) * 2 - 1,
               1 + 3 * uniform01(seed, i, 2)};
        spheres.push_back({c, 0.05 + 0.15 * uniform01(seed, i, 3)});
    }
    return spheres;
}

TEST(KanayamaLight, DomeWeightsAreANormalisedOvercastSky) {
    SkyDome dome = makeSkyDome(96);
    ASSERT_EQ(dome.directions.size(), 96u);
    double sum = 0, meanZ = 0;
    for (size_t k = 0; k < 96; ++k) {
        EXPECT_NEAR(length(dome.directions[k]), 1.0, 1e-12);
        EXPECT_GT(dome.directions[k].z, 0.0);
        sum += dome.weights[k];
        meanZ += dome.weights[k] * dome.directions[k].z;
    }
    EXPECT_NEAR(sum, 1.0, 1e-12);
    // CIE overcast: luminance (1 + 2 z) / 3 over equal solid angle in z = sin(elevation):
    // the light-weighted mean of z is int z (1 + 2z) dz / int (1 + 2z) dz = 7/12.
    EXPECT_NEAR(meanZ, 7.0 / 12.0, 0.02);  // one jittered sample per cell
}

TEST(KanayamaLight, EmbreeAgreesWithTheProjectionReference) {
    SkyDome dome = makeSkyDome(64);
    LeafLightParameters p;
    p.extinction = 8;
    LeafLightTracer tracer;
    for (uint64_t seed : {1u, 2u, 3u}) {
        std::vector<LeafSphere> spheres = randomCrown(seed, 300);
        std::vector<SphereLight> ref = leafLightReference(spheres, dome, p);
        std::vector<SphereLight> emb = tracer.compute(spheres, dome, p);
        LeafLightParameters packets = p;
        packets.packets = true;
        std::vector<SphereLight> emb16 = tracer.compute(spheres, dome, packets);
        ASSERT_EQ(ref.size(), emb.size());
        double darkest = 1;
        for (size_t i = 0; i < ref.size(); ++i) {
            // Same integer chord sums: equal up to float culling of grazing hits.
            EXPECT_NEAR(emb[i].light, ref[i].light, 1e-9) << "sphere " << i;
            EXPECT_NEAR(emb16[i].light, ref[i].light, 1e-9) << "sphere " << i;
            EXPECT_NEAR(dot(emb[i].brightestDirection, ref[i].brightestDirection), 1.0, 1e-9);
            darkest = std::min(darkest, ref[i].light);
        }
        EXPECT_LT(darkest, 0.5);  // the crown really shades itself
    }
}

TEST(KanayamaLight, ResultDoesNotDependOnThreadCount) {
    SkyDome dome = makeSkyDome(48);
    std::vector<LeafSphere> spheres = randomCrown(7, 500);
    LeafLightTracer tracer;
    LeafLightParameters one, two;
    one.threads = 1;
    two.threads = 2;
    std::vector<SphereLight> a = tracer.compute(spheres, dome, one);
    std::vector<SphereLight> b = tracer.compute(spheres, dome, two);
    for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].light, b[i].light);
        EXPECT_EQ(a[i].brightestDirection, b[i].brightestDirection);
    }
}

TEST(KanayamaLight, SphereUnderABigSphereGetsLessLight) {
    SkyDome dome = makeSkyDome(256);
    LeafLightParameters p;
    p.extinction = 20;
    // Sphere 0 sits 1 m under a 0.8 m sphere; sphere 2 is far off to the side, open sky.
    std::vector<LeafSphere> spheres{{{0, 0, 1}, 0.1}, {{0, 0, 2}, 0.8}, {{50, 0, 1}, 0.1}};
    LeafLightTracer tracer;
    std::vector<SphereLight> light = tracer.compute(spheres, dome, p);
    EXPECT_NEAR(light[2].light, 1.0, 1e-9);  // unshaded: the whole dome
    EXPECT_LT(light[0].light, 0.75 * light[2].light);
    // The shaded sphere's brightest direction leans away from the zenith, the open one's not.
    EXPECT_LT(light[0].brightestDirection.z, light[2].brightestDirection.z);
    // Analytic check: the big sphere subtends asin(0.8) = 53 deg around the zenith; with
    // extinction 20/m a chord of > 0.2 m is nearly opaque, so the light is about the sky
    // outside that cap: 1 - share of the CIE sky within z > cos(53 deg) = 0.6.
    double zc = 0.6, cap = ((1 - zc) + (1 - zc * zc)) / 2.0;  // integral of (1+2z)/3 dz, /1
    EXPECT_NEAR(light[0].light, 1 - cap, 0.08);
}

TEST(KanayamaLight, BrightnessScalesLight) {
    SkyDome dome = makeSkyDome(32);
    std::vector<LeafSphere> spheres = randomCrown(4, 50);
    LeafLightParameters p, dim;
    dim.brightness = 0.5;
    LeafLightTracer tracer;
    auto a = tracer.compute(spheres, dome, p);
    auto b = tracer.compute(spheres, dome, dim);
    for (size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(b[i].light, 0.5 * a[i].light, 1e-12);
}

}  // namespace
}  // namespace nenrin
