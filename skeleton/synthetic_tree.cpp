#include "skeleton/synthetic_tree.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "util/hash.h"

namespace nenrin {

Skeleton makeSyntheticTree(const SyntheticTreeOptions& o) {
    SplitMix rng(o.seed);
    Skeleton sk;
    size_t trunkSegs = std::max<size_t>(1, std::min(o.trunkSegments, o.totalSegments));
    std::vector<Vec3> trunk;
    std::vector<double> births;
    double phase = rng.uniform(0, 2 * std::numbers::pi);
    double prevZ = 0, t = 0;
    Vec3 prev{};
    for (size_t i = 0; i <= trunkSegs; ++i) {
        double z = o.height * static_cast<double>(i) / static_cast<double>(trunkSegs);
        // A slow sway of the pith, a few centimetres: real logs are never straight.
        Vec3 p{0.03 * std::sin(z * 0.7 + phase), 0.03 * std::cos(z * 0.5 + 2 * phase), z};
        if (i > 0) t += length(p - prev) / o.elongationSpeed;
        trunk.push_back(p);
        births.push_back(t);
        prev = p;
        prevZ = z;
    }
    (void)prevZ;
    sk.addTrunk(trunk, births);

    size_t perBranch = std::max<size_t>(1, o.segmentsPerBranch);
    size_t branchCount =
        o.totalSegments > trunkSegs ? (o.totalSegments - trunkSegs) / perBranch : 0;
    for (size_t b = 0; b < branchCount; ++b) {
        // Branches in the upper 85% of the trunk, a random azimuth, rising 10-60 degrees.
        double h = o.height * (0.1 + 0.85 * rng.uniform());
        uint32_t seg = std::min<uint32_t>(static_cast<uint32_t>(h / o.height * trunkSegs),
                                          static_cast<uint32_t>(trunkSegs - 1));
        const auto& s = sk.segment(seg);
        double f = rng.uniform();
        Vec3 start = lerp(sk.start(s), sk.end(s), f);
        double birth =
            sk.node(s.from).birthTime + (sk.node(s.to).birthTime - sk.node(s.from).birthTime) * f;
        double az = rng.uniform(0, 2 * std::numbers::pi);
        double el = rng.uniform(10, 60) * std::numbers::pi / 180;
        double len = o.branchLength * rng.uniform(0.5, 1.5);
        double droop = rng.uniform(0, 0.8);  // branches bend down towards their tips
        std::vector<Vec3> pts{start};
        std::vector<double> bt{birth};
        Vec3 p = start;
        for (size_t k = 1; k <= perBranch; ++k) {
            double u = static_cast<double>(k) / static_cast<double>(perBranch);
            double e = el - droop * u;
            Vec3 d{std::cos(e) * std::cos(az), std::cos(e) * std::sin(az), std::sin(e)};
            Vec3 q = p + d * (len / static_cast<double>(perBranch));
            bt.push_back(bt.back() + length(q - p) / o.elongationSpeed);
            pts.push_back(q);
            p = q;
        }
        ChainProperties props;
        props.gamma = rng.uniform(0.3, 0.8);
        if (rng.uniform() < o.deadFraction) {
            props.deathTime = birth + rng.uniform(3, 15);
            props.diebackExponent = rng.uniform(1, 3);
        }
        sk.addBranch(seg, pts, bt, props);
    }
    return sk;
}

}  // namespace nenrin
