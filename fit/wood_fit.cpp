#include "fit/wood_fit.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "fit/anatomy_tone.h"
#include "fit/cross_dating.h"
#include "fit/end_grain_tint.h"
#include "fit/fitted_grain.h"
#include "fit/knot_colour.h"
#include "fit/knot_halo.h"
#include "fit/knot_rings.h"
#include "fit/profile_sharpening.h"
#include "fit/texture_match.h"
#include "grain/grain_params.h"
#include "grain/grown_tree.h"
#include "grain/wood_colour.h"
#include "renderer/bake/bake_specs.h"
#include "renderer/bake/grid_bake.h"
#include "renderer/stats/image_statistics.h"
#include "renderer/stats/stats_image.h"
#include "shader/wood_shader.h"
#include "util/input_error.h"
#include "util/json_parse.h"
#include "util/progress.h"

namespace nenrin {

namespace {

/// Past this misfit the rings are not cylinders around one line (a knot, a crotch, much
/// figure): a warning; past the second, nothing in the photos is rings: an error.
constexpr double kPoorMisfitDeg = 20, kNoRingsMisfitDeg = 30;
/// Past this distance the rings are nearly straight: their curvature barely places the pith.
constexpr double kFarPith = 1.0;

double rounded(double v, double unit) { return std::round(v / unit) * unit; }

/// A straight trunk along the pith line, far past the sample both ways, born at once (rings
/// are then cylinders: T depends on the distance from the line only), with the ring series.
Skeleton pithSkeleton(const PithLine& pith, const RadialRings& profile) {
    const double reach = 1 + profile.outerRadius;
    Skeleton s;
    s.addTrunk({pith.point - pith.direction * reach, pith.point + pith.direction * reach}, {0, 0});
    s.setRingWidths(ringSeries(profile.boundaries, profile.outerRadius));
    return s;
}

/// Rounds of colour calibration at most.
constexpr int kColourRounds = 3;
constexpr int kKnotColourRounds = 2;

/// The face baked through the fitted wood at the statistics' scale, measured against its
/// photograph.
FaceFigures measureFace(const WoodShader& shader, const Skeleton& skeleton, const FacePhoto& photo,
                        const FitOptions& options) {
    const SampleFace& face = *photo.face;
    FaceFigures f;
    f.name = face.name;
    f.heldOut = std::find(options.heldOut.begin(), options.heldOut.end(), face.name) !=
                options.heldOut.end();
    SliceSpec spec;
    spec.cut = PlaneCut{face.origin, face.right, face.up};
    spec.resX = spec.resY = kStatsSize;
    f.bake = sliceGrid(skeleton, spec);
    bakeGrid(shader, f.bake, {options.threads, true, "Baking " + face.name});
    Plane growthTime(kStatsSize, kStatsSize);
    std::array<Plane, 3> rgb;
    for (Plane& p : rgb) p = Plane(kStatsSize, kStatsSize);
    for (int y = 0; y < kStatsSize; ++y)
        for (int x = 0; x < kStatsSize; ++x) {
            const float* v = f.bake.at(x, y);
            for (int c = 0; c < 3; ++c) rgb[size_t(c)].at(x, y) = std::max(0.0f, v[c]);
            growthTime.at(x, y) = v[4];
        }
    const RingAgreement rings = ringAgreement(photo.structure, growthTime, face.image);
    f.ringMedianDeg = rings.medianDeg;
    f.ringWithin15 = rings.within15;
    const std::array<Plane, 3> bakedLab = labPlanes(rgb);
    f.lightness = bakedLab[0];
    // (The fit compares colour and texture energy only: dir_spread and fine_aniso stay 0.)
    const ImageStatistics baked =
        roundedAsReported(imageStatistics(bakedLab, Figures::kColourAndEnergy));
    const StatisticsAgainst against = statisticsAgainst(baked, photo.figures, face.image);
    f.dE = against.dE;
    f.fineRatio = against.fineRatio;
    f.midRatio = against.midRatio;
    f.photo = photo.linear;
    return f;
}

/// Bakes every face of the grain; then, `rounds` times at most, scales its early and late wood
/// colours until the bakes of the fitted faces have the photos' mean colour (the strip's
/// colours are the photo's; the bake adds the finish and the anatomy's texture, which darken
/// it). Returns the last bakes.
std::vector<FaceFigures> calibrateColours(nlohmann::json& grain, const Skeleton& skeleton,
                                          const std::vector<FacePhoto>& photos,
                                          const FitOptions& options, int rounds) {
    std::vector<FaceFigures> faces;
    for (int round = 0;; ++round) {
        const GrownTree tree(Skeleton(skeleton), parseGrain(grain, "the fitted grain"));
        const WoodShader shader(tree.field());
        faces.clear();
        for (const FacePhoto& p : photos)
            faces.push_back(measureFace(shader, skeleton, p, options));
        const Rgb ratio = colourRatio(faces);
        if (round == rounds || worstLog(ratio) < 0.005) return faces;
        scaleWoodColours(grain, ratio);
    }
}

/// How far the bakes' texture is from the photos': the squared logarithms of the fine and mid
/// energy ratios, summed over the fitted faces.
double textureMisfit(const std::vector<FaceFigures>& faces) {
    double sum = 0;
    for (const FaceFigures& f : faces) {
        if (f.heldOut) continue;
        for (double ratio : {f.fineRatio, f.midRatio})
            sum += ratio > 0 ? std::pow(std::log(ratio), 2) : 100.0;
    }
    return sum;
}

/// Each face's end-grain weight, as the shader weighs it with the fibre along the pith.
std::vector<double> endGrainWeights(std::span<const FacePhoto> photos, const PithLine& pith) {
    std::vector<double> weights;
    for (const FacePhoto& p : photos) {
        const Vec3 normal = normalize(cross(p.face->right, p.face->up));
        weights.push_back(endGrainWeight(std::abs(dot(normal, pith.direction))));
    }
    return weights;
}

/// Each photograph's strongest ring centre, found once (whether it is a knot depends on the
/// pith line, which the knots move).
using RingCentres = std::vector<std::optional<FaceKnot>>;
RingCentres ringCentres(std::span<const FacePhoto> photos) {
    RingCentres centres;
    for (const FacePhoto& p : photos) centres.push_back(strongestRingCentre(p.lightness, *p.face));
    return centres;
}

/// The knots the fitted photos show, one per face at most.
std::vector<FaceKnot> seenKnots(const RingCentres& centres, const PithLine& pith,
                                const FitOptions& options) {
    std::vector<FaceKnot> knots;
    for (const std::optional<FaceKnot>& c : centres)
        if (c && looksLikeKnot(*c, &pith) &&
            std::find(options.heldOut.begin(), options.heldOut.end(), c->face) ==
                options.heldOut.end())
            knots.push_back(*c);
    return knots;
}

/// Leaves out the ring directions (and fine gradients) within twice a knot's radius of its
/// centre: there the rings circle the branch, not the pith, and would pull the pith line and
/// the warp (a knot face's tilt went 29 degrees off).
void maskKnots(std::vector<FacePhoto>& photos, std::span<const FaceKnot> knots) {
    for (FacePhoto& p : photos)
        for (const FaceKnot& k : knots) {
            if (k.face != p.face->name) continue;
            const double reach = std::max(2 * k.radius, 0.005);
            size_t kept = 0;
            for (size_t i = 0; i < p.directions.size(); ++i)
                if (length(p.directions[i].position - k.centre) > reach) {
                    p.directions[kept] = p.directions[i];
                    p.fineGradients[kept] = p.fineGradients[i];
                    ++kept;
                }
            p.directions.resize(kept);
            p.fineGradients.resize(kept);
        }
}

/// Every face whose photograph shows a knot, with the bake's ring centre there.
std::vector<KnotFigures> knotFigures(std::span<const FacePhoto> photos, const RingCentres& centres,
                                     const std::vector<FaceFigures>& faces, const PithLine& pith) {
    std::vector<KnotFigures> knots;
    for (size_t i = 0; i < photos.size(); ++i) {
        if (!centres[i] || !looksLikeKnot(*centres[i], &pith)) continue;
        KnotFigures k;
        k.heldOut = faces[i].heldOut;
        k.photo = *centres[i];
        k.baked = strongestRingCentre(faces[i].lightness, *photos[i].face);
        if (k.baked) k.offsetMm = 1e3 * length(k.baked->centre - k.photo.centre);
        knots.push_back(k);
    }
    return knots;
}

/// Where a branch crosses a face is not quite where its knot's rings centre in the bake (an
/// oblique cone's section is an eccentric oval; the junction blend bends the rings): moves
/// each knot's aim by the bake's miss (0.2-3 mm) so that a branch through the aims bakes its
/// knots onto the photos'. True when an aim moved.
bool aimKnots(std::vector<FaceKnot>& aims, const std::vector<KnotFigures>& baked) {
    bool moved = false;
    for (FaceKnot& aim : aims)
        for (const KnotFigures& k : baked) {
            if (k.photo.face != aim.face || !k.baked) continue;
            const Vec3 miss = k.photo.centre - k.baked->centre;
            if (length(miss) < 2e-4 || length(miss) > 3e-3) continue;
            aim.centre = aim.centre + miss;
            moved = true;
        }
    return moved;
}

nlohmann::json pointJson(const Vec3& p) {
    return {rounded(p.x, 1e-6), rounded(p.y, 1e-6), rounded(p.z, 1e-6)};
}

nlohmann::json knotJson(const FaceKnot& k) {
    return {{"column", rounded(k.column, 0.01)},
            {"row", rounded(k.row, 0.01)},
            {"centre", pointJson(k.centre)},
            {"radius_mm", rounded(k.radius * 1e3, 0.01)},
            {"evidence", rounded(k.evidence, 0.01)},
            {"coverage", k.coverage},
            {"darkening", rounded(k.darkening, 0.01)},
            {"roundness", rounded(k.roundness, 0.001)},
            {"ring_spacing_mm", rounded(k.ringSpacing * 1e3, 0.01)},
            {"long_axis", pointJson(k.longAxis)}};
}

double meanRingWidth(const RadialRings& profile) {
    const std::vector<double>& b = profile.boundaries;
    return (b.back() - b.front()) / double(std::max<size_t>(1, b.size() - 1));
}

/// The knot found on the face named `face` (at most one per face), or null.
const FaceKnot* knotOnFace(const std::vector<FaceKnot>& knots, const std::string& face) {
    const auto k =
        std::find_if(knots.begin(), knots.end(), [&](const FaceKnot& x) { return x.face == face; });
    return k == knots.end() ? nullptr : &*k;
}

/// The faces to read the ring series on: those without a knot, if any (a knot's dark wood
/// and its own rings make the clearest strip, and the wrong one).
std::vector<FacePhoto> ringFaces(const std::vector<FacePhoto>& fitted,
                                 const std::vector<FaceKnot>& knots) {
    std::vector<FacePhoto> plain;
    for (const FacePhoto& p : fitted)
        if (!knotOnFace(knots, p.face->name)) plain.push_back(p);
    return plain.empty() ? fitted : plain;
}

/// --leave-out names faces of the sample, and not all of them.
void checkHeldOut(const Sample& sample, const FitOptions& options) {
    for (const std::string& name : options.heldOut)
        if (std::none_of(sample.faces.begin(), sample.faces.end(),
                         [&](const SampleFace& f) { return f.name == name; }))
            throw InputError("command line", "--leave-out",
                             fmt::format("{} has no face named {}", sample.file, name));
    if (std::all_of(sample.faces.begin(), sample.faces.end(), [&](const SampleFace& f) {
            return std::find(options.heldOut.begin(), options.heldOut.end(), f.name) !=
                   options.heldOut.end();
        }))
        throw InputError("command line", "--leave-out", "every face is left out: nothing to fit");
}

/// The skeleton: the trunk along the pith line and a branch for each knot (or pair of faces'
/// knots).
void placeBranches(WoodFit& fit, const std::vector<FaceKnot>& knots, const Sample& sample) {
    const std::vector<KnotBranch> sized = fit.branches;
    fit.branches =
        knotBranches(knots, fit.pith, sample.faces, fit.pith.distance + length(sample.size) + 0.01,
                     meanRingWidth(fit.profile));
    // Branches placed again keep the sizes found for them, with the knot they were found on:
    // the birth is the year the tip passed that knot (when two faces' knots are crossed about
    // as squarely, the new line may prefer the other, farther out along the branch).
    for (KnotBranch& b : fit.branches)
        for (const KnotBranch& old : sized)
            if (old.faces == b.faces) {
                b.gamma = old.gamma, b.birth = old.birth;
                b.sizedBy = old.sizedBy, b.sizedAt = old.sizedAt, b.radius = old.radius;
            }
    fit.skeleton = pithSkeleton(fit.pith, fit.profile);
    addKnotBranches(fit.skeleton, fit.branches);
}

/// Rounds of knot sizing.
constexpr int kKnotSizeRounds = 2;

/// Moves each branch's birth so that its knots in the bakes are as large as in the photos:
/// a knot's radius is about gamma (r - t w) (eq. 3', w the ring width), so the year t the tip
/// passed it moves by the radii's difference over gamma w. (The radius the knot finder
/// measures is its dark wood's, inside the branch's share: the first estimate of t makes the
/// knots too small.) A branch through two faces takes both faces' moves, each carried to the
/// sizing knot by the ratio of the paths from the pith (its birth times grow in proportion to
/// the path) and weighed by how squarely the branch crosses the face: one knot's radius is
/// read a tenth off now and then (its faint rings under the texture), and a branch crossing
/// two faces about as squarely took whichever such reading came first. Leaves the skeleton
/// rebuilt.
void sizeKnots(WoodFit& fit, const std::vector<FacePhoto>& photos,
               const std::vector<FaceKnot>& knots, const FitOptions& options) {
    const double ringWidth = meanRingWidth(fit.profile);
    for (int round = 0; round < kKnotSizeRounds; ++round) {
        const GrownTree tree(Skeleton(fit.skeleton), parseGrain(fit.grain, "the fitted grain"));
        const WoodShader shader(tree.field());
        for (KnotBranch& b : fit.branches) {
            if (b.points.empty()) continue;
            const Vec3 u = normalize(b.points.back() - b.start);
            const double sizerPath = length(b.sizedAt - b.start);
            double moves = 0, weights = 0;
            for (const FacePhoto& p : photos) {
                // The branch's photographed knot on this face (the sizing one among them).
                const FaceKnot* k = knotOnFace(knots, p.face->name);
                if (!k || std::find(b.faces.begin(), b.faces.end(), p.face->name) == b.faces.end())
                    continue;
                const Vec3 centre = k->centre;
                const double radius = k->radius;
                const double path = length(centre - b.start);
                if (!(path > 0) || !(radius > 0)) continue;
                const FaceFigures f = measureFace(shader, fit.skeleton, p, options);
                const std::optional<FaceKnot> baked = strongestRingCentre(f.lightness, *p.face);
                if (!baked || length(baked->centre - centre) > radius) continue;
                const double square = std::abs(dot(u, p.face->normal()));
                moves +=
                    square * (radius - baked->radius) / (b.gamma * ringWidth) * sizerPath / path;
                weights += square;
            }
            // (Not past the year the trunk's bark reached the knot: it would vanish.)
            if (weights > 0)
                b.birth = std::clamp(b.birth - moves / weights, 0.0,
                                     ringRadius(fit.pith, b.sizedAt) / ringWidth);
        }
        fit.skeleton = pithSkeleton(fit.pith, fit.profile);
        addKnotBranches(fit.skeleton, fit.branches);
    }
}

/// The knots' wood coloured as photographed (two rounds: the knot share's smoothstep blends
/// the knot colour in, so one ratio undershoots), then their rings' contrast (the late wood
/// darkened) and their mean colour again.
void colourKnots(WoodFit& fit, const std::vector<FacePhoto>& photos, const FitOptions& options) {
    auto rebake = [&] { return calibrateColours(fit.grain, fit.skeleton, photos, options, 0); };
    auto matchColour = [&] {
        for (int round = 0; round < kKnotColourRounds; ++round) {
            if (!matchKnotColour(fit.grain, fit.faces)) break;
            fit.faces = rebake();
        }
    };
    matchColour();
    matchKnotRings(fit.grain, fit.faces, photos, rebake);
    matchColour();
    fit.knotRings = knotRingContrast(photos, fit.faces);
}

/// The anatomy's tone out of the chosen grain's ring profile (fit/anatomy_tone.h), and the
/// colours calibrated again; fit.faces are the bakes of fit.grain before and after.
void takeOutAnatomyTone(WoodFit& fit, const std::vector<FacePhoto>& photos,
                        const FitOptions& options) {
    if (!fit.grain.contains("anatomy")) return;
    nlohmann::json plain = fit.grain;
    plain.erase("anatomy");
    const std::vector<FaceFigures> without =
        calibrateColours(plain, fit.skeleton, photos, options, 0);
    const size_t n = fit.grain["colour"].value("late_wood_profile", nlohmann::json::array()).size();
    fit.anatomyTone = anatomyTone(fit.faces, without, n);
    if (removeAnatomyTone(fit.grain, fit.anatomyTone))
        fit.faces = calibrateColours(fit.grain, fit.skeleton, photos, options, kColourRounds);
}

/// Refuses photographs whose rings fit no line at all (not wood, or faces placed wrongly);
/// warns of a poor fit and of a far pith.
void judgePithLine(const PithLine& pith, const std::string& sampleFile,
                   std::vector<std::string>& warnings) {
    if (pith.medianMisfitDeg > kNoRingsMisfitDeg)
        throw InputError(
            sampleFile, "faces",
            fmt::format("the photographs show no rings around any line (median misfit {:.0f} "
                        "degrees; random directions give 45): not wood, or faces placed wrongly",
                        pith.medianMisfitDeg));
    if (pith.medianMisfitDeg > kPoorMisfitDeg)
        warnings.push_back(fmt::format(
            "the rings are not cylinders around one pith line: median misfit {:.1f} degrees "
            "(photos of another material, faces that contradict each other, or much figure)",
            pith.medianMisfitDeg));
    if (pith.distance > kFarPith)
        warnings.push_back(fmt::format(
            "the rings are nearly straight: the pith lies {:.2f} m away and its distance is "
            "uncertain",
            pith.distance));
}

}  // namespace

WoodFit fitSample(const Sample& sample, const FitOptions& options) {
    const auto start = std::chrono::steady_clock::now();
    checkHeldOut(sample, options);
    std::vector<FacePhoto> photos, fitted;
    for (const SampleFace& face : sample.faces) photos.push_back(readFacePhoto(face));
    for (const FacePhoto& p : photos)
        if (std::find(options.heldOut.begin(), options.heldOut.end(), p.face->name) ==
            options.heldOut.end())
            fitted.push_back(p);

    const size_t baseCount = std::max<size_t>(1, options.baseGrains.size());
    ProgressReporter progress(static_cast<long long>(3 + baseCount), "Fitting", options.quiet);
    WoodFit fit;
    fit.pith = focusPithLine(
        crossDatePithLine(fitPithLine(fitted, sample.file), fitted, options.threads), fitted);
    progress.advance();
    // Knots: their rings circle their branches; left out of the pith, warp and ring fits, and
    // each made a branch of the skeleton.
    const RingCentres centres = options.knots ? ringCentres(photos) : RingCentres(photos.size());
    const std::vector<FaceKnot> knots = seenKnots(centres, fit.pith, options);
    if (!knots.empty()) {
        maskKnots(fitted, knots);
        // Fitted again without the knots' rings, kept if it fits the rest better (with few
        // faces left the line can wander off).
        const PithLine again = focusPithLine(
            crossDatePithLine(fitPithLine(fitted, sample.file), fitted, options.threads), fitted);
        const double kept = pithMisfitDeg(fit.pith, fitted),
                     refitted = pithMisfitDeg(again, fitted);
        if (refitted < kept) fit.pith = again;
        // The line's misfit as the rest of the fit sees the faces: without the knots' rings.
        fit.pith.medianMisfitDeg = std::min(kept, refitted);
    }
    // Judged on the line kept: the first one, with the knots' rings in, can fit far worse
    // (H11 with D left out: 27.7 degrees before its knots were left out, 7.2 after) or lie
    // elsewhere (with B left out: 2.43 m away, the line kept 37 mm).
    judgePithLine(fit.pith, sample.file, fit.warnings);
    fit.warp = fitRingWarp(fitted, fit.pith);
    progress.advance();
    fit.profile = measureRadialRings(ringFaces(fitted, knots), fit.pith, fit.warp, sample.file);
    // The shells' average blurs the late-wood line; undone by the width of the ring boundary.
    const SharpenedProfile sharpened = sharpenLateWoodProfile(fit.profile.strip.lateWoodProfile);
    fit.profile.strip.lateWoodProfile = sharpened.profile;
    fit.profileBlur = sharpened.blur;
    progress.advance();
    if (fit.profile.evenRings)
        fit.warnings.push_back(fmt::format(
            "no face shows 3 whole rings across it: the rings are taken as even, {:.2f} mm wide "
            "(their period in the photographs); an end-grain face would measure them",
            1e3 * (fit.profile.boundaries.back() - fit.profile.boundaries.front()) /
                double(std::max<size_t>(1, fit.profile.boundaries.size() - 1))));
    placeBranches(fit, knots, sample);
    // The anatomy (the texture) comes from a base grain: of several, the one whose bakes'
    // fine and mid texture come nearest the photos'.
    const std::vector<std::string> bases =
        options.baseGrains.empty() ? std::vector<std::string>{""} : options.baseGrains;
    double bestScore = std::numeric_limits<double>::infinity();
    for (const std::string& base : bases) {
        nlohmann::json grain = fittedGrain(base, sample, fit.profile);
        GrainParams warped = parseGrain(grain, "the fitted grain");
        warped.warp = grainWarp(fit.warp, sample.size * -0.55, sample.size * 0.55);
        grain["warp"] = grainToJson(warped)["warp"];
        const std::vector<FaceFigures> faces =
            calibrateColours(grain, fit.skeleton, photos, options, bases.size() > 1 ? 1 : 3);
        const double score = textureMisfit(faces);
        if (score < bestScore)
            bestScore = score, fit.grain = grain, fit.faces = faces, fit.base = base;
    }
    takeOutAnatomyTone(fit, photos, options);
    if (!fit.branches.empty()) {
        sizeKnots(fit, photos, knots, options);
        fit.faces = calibrateColours(fit.grain, fit.skeleton, photos, options, 0);
    }
    std::vector<FaceKnot> aimed = knots;
    const bool aim = aimKnots(aimed, knotFigures(photos, centres, fit.faces, fit.pith));
    if (aim) placeBranches(fit, aimed, sample);
    if (aim || bases.size() > 1)
        fit.faces = calibrateColours(fit.grain, fit.skeleton, photos, options, 3);
    const std::vector<double> endWeights = endGrainWeights(photos, fit.pith);
    auto rebake = [&] { return calibrateColours(fit.grain, fit.skeleton, photos, options, 0); };
    fit.texture = matchTexture(fit.grain, fit.faces, endWeights, rebake);
    if (fit.texture.bakes > 0)
        fit.faces = calibrateColours(fit.grain, fit.skeleton, photos, options, kColourRounds);
    matchEndGrainTint(fit.grain, fit.faces, endWeights, rebake, kColourRounds);
    if (!fit.branches.empty()) {
        // The stem wood round the knots, the wood's colours again for the means it moved,
        // then the knots' own wood.
        fit.halo = matchKnotHalo(fit.grain, fit.faces, rebake);
        if (fit.halo.kept)
            fit.faces = calibrateColours(fit.grain, fit.skeleton, photos, options, kColourRounds);
        colourKnots(fit, photos, options);
    }
    fit.knots = knotFigures(photos, centres, fit.faces, fit.pith);
    fit.grain = withBaseLook(std::move(fit.grain), fit.base);
    if (options.baseGrains.empty())
        fit.warnings.push_back(
            "no base grain (--grain): the bakes carry no anatomy (fibres, pores, rays); give "
            "species presets to take it from");
    fit.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return fit;
}

nlohmann::json fitReport(const Sample& sample, const WoodFit& fit) {
    nlohmann::json faces = nlohmann::json::array();
    for (const FaceFigures& f : fit.faces)
        faces.push_back({{"name", f.name},
                         {"held_out", f.heldOut},
                         {"ring_median_deg", f.ringMedianDeg},
                         {"ring_within_15", f.ringWithin15},
                         {"dE", f.dE},
                         {"fine_ratio", f.fineRatio},
                         {"mid_ratio", f.midRatio}});
    nlohmann::json branches = nlohmann::json::array(), seen = nlohmann::json::array();
    for (const KnotBranch& b : fit.branches) {
        nlohmann::json points = nlohmann::json::array();
        for (const Vec3& q : b.points) points.push_back(pointJson(q));
        branches.push_back({{"faces", b.faces},
                            {"start", pointJson(b.start)},
                            {"points", points},
                            {"gamma", rounded(b.gamma, 1e-4)},
                            {"birth_years", rounded(b.birth, 0.01)},
                            {"sized_by", b.sizedBy},
                            {"photo_radius_mm", rounded(b.radius * 1e3, 0.01)}});
    }
    for (const KnotFigures& k : fit.knots)
        seen.push_back({{"face", k.photo.face},
                        {"held_out", k.heldOut},
                        {"photo", knotJson(k.photo)},
                        {"baked", k.baked ? knotJson(*k.baked) : nlohmann::json(nullptr)},
                        {"offset_mm", rounded(k.offsetMm, 0.01)}});
    nlohmann::json knotsJson = {{"branches", branches}, {"faces", seen}};
    if (fit.knotRings.pixels > 0)
        knotsJson["ring_contrast"] = {{"photo", rounded(fit.knotRings.photo, 0.01)},
                                      {"baked", rounded(fit.knotRings.baked, 0.01)},
                                      {"pixels", fit.knotRings.pixels}};
    if (fit.halo.bakes > 0)
        knotsJson["halo"] = {{"kept", fit.halo.kept},
                             {"width", fit.halo.width},
                             {"axial", fit.halo.axial},
                             {"bakes", fit.halo.bakes}};
    const PithLine& p = fit.pith;
    nlohmann::json widths = nlohmann::json::array();
    const std::vector<double>& b = fit.profile.boundaries;
    for (size_t k = 1; k < b.size(); ++k) widths.push_back(rounded(b[k] - b[k - 1], 1e-6));
    nlohmann::json boundaries = nlohmann::json::array();
    for (double r : b) boundaries.push_back(rounded(r, 1e-6));
    nlohmann::json tone = nlohmann::json::array();
    for (double t : fit.anatomyTone) tone.push_back(rounded(t, 1e-3));
    return {{"format", "nenrin-fit"},
            {"sample", sample.file},
            {"seconds", rounded(fit.seconds, 0.01)},
            {"pith",
             {{"point", {p.point.x, p.point.y, p.point.z}},
              {"direction", {p.direction.x, p.direction.y, p.direction.z}},
              {"distance", p.distance},
              {"median_misfit_deg", rounded(p.medianMisfitDeg, 0.01)}}},
            {"rings",
             {{"count", fit.profile.strip.rings},
              {"measured_on_face", fit.profile.face},
              {"boundary_radii", boundaries},
              {"widths", widths},
              {"late_wood_blur", rounded(fit.profileBlur, 1e-4)},
              {"anatomy_tone", tone},
              {"inner_radius", fit.profile.innerRadius},
              {"outer_radius", fit.profile.outerRadius}}},
            {"knots", knotsJson},
            {"anatomy_from", fit.base},
            {"texture_strengths",
             {{"side_cells", fit.texture.sideCells},
              {"end_cells", fit.texture.endCells},
              {"end_rest", fit.texture.endRest},
              {"bakes", fit.texture.bakes}}},
            {"faces", faces},
            {"warnings", fit.warnings}};
}

}  // namespace nenrin
