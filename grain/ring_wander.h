#pragma once
/// Rings that wander: a seeded, smooth 3-D displacement of the point the field is evaluated at,
/// at the 1-3 cm scale of real wood (the chestnut cube's rings wave by a millimetre or two over
/// a centimetre; a hinoki board's ring arcs bend at that scale), on top of the decimetre-scale
/// sway of section 4.5. It is one continuous field over the whole tree, so a board and the
/// next board cut from the log agree where they meet, and rings on opposite sides of the pith
/// wander independently (no mirror images). Fibres follow: they lie in the displaced ring
/// surfaces (the shader takes them from grad T). Units: metres.

#include <array>
#include <cstdint>

#include "util/value_noise.h"
#include "util/vec3.h"

namespace nenrin {

struct WanderParams {
    double amplitude = 0;      ///< m: the largest displacement (0 = off)
    double wavelength = 0.02;  ///< m: across the fibre (tangential and radial)
    double along = 0.04;       ///< m: along the trunk (tree Z); real waves are longer there
    int octaves = 2;           ///< each twice as fine and half as strong as the last
    uint64_t seed = 1;
};

/// The displacement at p (each component at most `amplitude`).
Vec3 ringWander(const Vec3& p, const WanderParams& wander);

/// ringWander at many nearby points (a batch of the field): each octave keeps its last lattice
/// cell, so neighbouring points share its hashing. The same bits as ringWander.
class RingWander {
public:
    explicit RingWander(const WanderParams& wander);
    Vec3 operator()(const Vec3& p);

private:
    WanderParams w_;
    std::array<ValueNoise3Cache, 4> octaves_;  ///< octaves are 1 to 4 (grain_params.cpp)
};

}  // namespace nenrin
