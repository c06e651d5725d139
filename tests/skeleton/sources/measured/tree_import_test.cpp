#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "skeleton/skeleton_file.h"
#include "skeleton/skeleton_writer.h"
#include "skeleton/sources/measured/gran1_import.h"
#include "skeleton/sources/measured/qsm_import.h"
#include "tests/scratch_path.h"
#include "util/input_error.h"
#include "util/json_reader.h"

namespace nenrin {
namespace {

const std::string kGran1 = std::string(NENRIN_SOURCE_DIR) + "/data/gran1/Gran_1";

double wrapAngle(double a) { return std::remainder(a, 2 * std::numbers::pi); }

TEST(Gran1Import, EveryKnotAtItsMeasuredHeightAndAzimuth) {
    Gran1Log log = importGran1(kGran1);
    nlohmann::json knots = parseJsonFile(kGran1 + "_knots.json");
    nlohmann::json pith = parseJsonFile(kGran1 + "_pith.json");
    ASSERT_EQ(knots.size(), 108u);
    EXPECT_EQ(log.knotsSkipped, 0u);  // no Gran_1 knot died at once (I >= 32 mm)
    ASSERT_EQ(log.knots, 108u);
    ASSERT_EQ(log.skeleton.chains().size(), 109u);
    const Skeleton& sk = log.skeleton;
    double baseZ = pith[0][2].get<double>();
    size_t alive = 0;
    for (size_t k = 0; k < knots.size(); ++k) {
        const auto& q = knots[k];
        double C = q[2], D = q[3], E = q[4], F = q[5], G = q[6], H = q[7], I = q[8];
        const SkeletonChain& chain = sk.chain(static_cast<uint32_t>(k + 1));
        EXPECT_EQ(chain.parentChain, 0);
        const SkeletonSegment& first = sk.segment(chain.firstSegment);
        const SkeletonSegment& last = sk.segment(chain.firstSegment + chain.segmentCount - 1);
        Vec3 start = sk.start(first), tip = sk.end(last);
        EXPECT_NEAR(start.z, (C - baseZ) * 1e-3, 1e-9) << "knot " << k;
        // The tip: H mm out from the pith, at azimuth F + G ln H and height C + D√H + E H.
        Vec3 out = tip - start;
        EXPECT_NEAR(std::hypot(out.x, out.y), H * 1e-3, 1e-9) << "knot " << k;
        EXPECT_NEAR(wrapAngle(std::atan2(out.y, out.x) - (F + G * std::log(H))), 0, 1e-9);
        EXPECT_NEAR(tip.z, (C + D * std::sqrt(H) + E * H - baseZ) * 1e-3, 1e-9);
        if (I >= H) {
            ++alive;
            EXPECT_EQ(first.deathTime, kNeverDies);
        } else {
            // It died when the stem, thickening one ring a year, reached I from the pith.
            EXPECT_NEAR((first.deathTime - sk.node(first.from).birthTime) * log.ringWidth, I * 1e-3,
                        1e-12);
        }
    }
    EXPECT_EQ(alive, 41u);
}

TEST(Gran1Import, RingWidthFitsTheBarkAndRoundTrips) {
    Gran1Options o;
    o.rings = 50;
    Gran1Log log = importGran1(kGran1, o);
    // The bark map's radii are 104…143 mm; the fitted butt radius lies inside.
    EXPECT_NEAR(log.minBarkRadius, 0.10406, 1e-4);
    EXPECT_NEAR(log.maxBarkRadius, 0.14338, 1e-4);
    EXPECT_GT(log.meanButtRadius, 0.12);
    EXPECT_LT(log.meanButtRadius, 0.13);
    EXPECT_NEAR(log.ringWidth * 50, log.meanButtRadius, 1e-12);
    EXPECT_GT(log.meanTopRadius, 0.11);
    EXPECT_LT(log.meanTopRadius, log.meanButtRadius);  // the log tapers upwards
    ASSERT_EQ(log.skeleton.ringWidths().size(), 50u);
    Skeleton back = parseSkeleton(skeletonToJson(log.skeleton, {}), "gran1.json");
    EXPECT_EQ(back.segments().size(), log.skeleton.segments().size());
}

TEST(Gran1Import, MissingOrBrokenFilesNameTheFile) {
    EXPECT_THROW(importGran1("/nonexistent/Gran_1"), InputError);
    Gran1Options bad;
    bad.rings = -3;
    EXPECT_THROW(importGran1(kGran1, bad), InputError);
    // A radius map of 1e308 mm once summed to Inf and wrote null radii the loader refused.
    const auto dir = scratchPath("gran1-huge");
    std::filesystem::create_directories(dir);
    for (const char* part : {"_pith.json", "_knots.json"})
        std::filesystem::copy_file(kGran1 + part, dir / (std::string("G") + part),
                                   std::filesystem::copy_options::overwrite_existing);
    nlohmann::json radii = parseJsonFile(kGran1 + "_radii.json");
    auto errorWithRadius = [&](double r) {
        radii[3][0] = r;
        std::ofstream(dir / "G_radii.json") << radii.dump();
        try {
            importGran1((dir / "G").string());
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(errorWithRadius(1e308).find("G_radii.json: [3][0]: 1e+308 is beyond"),
              std::string::npos);
    EXPECT_NE(errorWithRadius(2e4).find(
                  "G_radii.json: [3]: expected bark radii in (0, 10000] mm, found 20000"),
              std::string::npos);
    std::filesystem::remove_all(dir);
}

// A small QSM: a stem of four 1 m cylinders, a branch on the second cylinder with a
// sub-branch, and a branch on the fourth. TreeQSM columns: radius, length, start xyz, axis
// xyz, parent, extension, branch, order, position, added, unmodified radius.
const char* kQsm =
    "0.20\t1\t0\t0\t0\t0\t0\t1\t0\t2\t1\t0\t1\t0\t0.20\n"
    "0.18\t1\t0\t0\t1\t0\t0\t1\t1\t3\t1\t0\t2\t0\t0.18\n"
    "0.16\t1\t0\t0\t2\t0\t0\t1\t2\t4\t1\t0\t3\t0\t0.16\n"
    "0.14\t1\t0\t0\t3\t0\t0\t1\t3\t0\t1\t0\t4\t0\t0.14\n"
    "0.06\t1\t0.18\t0\t1.5\t1\t0\t0\t2\t6\t2\t1\t1\t0\t0.06\n"
    "0.05\t1\t1.18\t0\t1.5\t1\t0\t0.2\t5\t0\t2\t1\t2\t0\t0.05\n"
    "0.04\t0.5\t0\t0.14\t3.5\t0\t-1\t0\t4\t0\t3\t1\t1\t0\t0.04\n"
    "0.02\t0.3\t1.5\t0\t1.55\t0\t1\t0\t6\t0\t4\t2\t1\t0\t0.02\n";

TEST(QsmImport, KeepsTheParentStructure) {
    QsmTree t = parseQsm(kQsm, "tree.txt");
    const Skeleton& sk = t.skeleton;
    EXPECT_EQ(t.cylinders, 8u);
    ASSERT_EQ(t.branches, 4u);
    ASSERT_EQ(sk.chains().size(), 4u);
    EXPECT_EQ(t.branchIdOfChain, (std::vector<long long>{1, 2, 3, 4}));
    // The stem: one chain of four segments, radii from the cylinders.
    EXPECT_EQ(sk.chain(0).segmentCount, 4u);
    EXPECT_DOUBLE_EQ(sk.node(0).radius, 0.20);
    // Branch 2 starts on the second stem cylinder's axis, then goes out to the cylinder.
    const SkeletonChain& b2 = sk.chain(1);
    EXPECT_EQ(b2.parentChain, 0);
    EXPECT_EQ(b2.order, 1);
    const SkeletonSegment& b2first = sk.segment(b2.firstSegment);
    EXPECT_EQ(b2first.parent, 1);  // stem segment 1 = cylinder 2
    EXPECT_NEAR(length(sk.start(b2first) - Vec3{0, 0, 1.5}), 0, 1e-12);
    EXPECT_NEAR(b2first.gamma, 0.06 / 0.18, 1e-12);
    // Branch 3 starts on the fourth stem cylinder; branch 4 on branch 2's second cylinder.
    EXPECT_EQ(sk.chain(2).parentChain, 0);
    EXPECT_EQ(sk.segment(sk.chain(2).firstSegment).parent, 3);
    EXPECT_EQ(sk.chain(3).parentChain, 1);
    EXPECT_EQ(sk.chain(3).order, 2);
    const SkeletonSegment& b4first = sk.segment(sk.chain(3).firstSegment);
    EXPECT_EQ(sk.segment(static_cast<uint32_t>(b4first.parent)).chain, 1u);
    // It starts at the foot of the perpendicular from its first cylinder onto cylinder 6.
    Vec3 onParent = sk.start(b4first), axis = normalize(Vec3{1, 0, 0.2});
    EXPECT_NEAR(dot(Vec3{1.5, 0, 1.55} - onParent, axis), 0, 1e-12);
    EXPECT_NEAR(length(cross(onParent - Vec3{1.18, 0, 1.5}, axis)), 0, 1e-12);
    // Birth times follow path length at 0.5 m/year; the stem tip is 4 m up. The last tip is
    // branch 3's: 3.5 m of stem, 0.14 m to the cylinder, 0.5 m of cylinder = 8.28 years, so
    // the tree is 9 years old and the ring width is the base radius over 9.
    EXPECT_DOUBLE_EQ(sk.node(sk.segment(3).to).birthTime, 8.0);
    EXPECT_NEAR(sk.node(sk.segment(sk.chain(2).firstSegment + 1).to).birthTime, 8.28, 1e-12);
    EXPECT_EQ(t.age, 9.0);
    EXPECT_DOUBLE_EQ(t.ringWidth, 0.2 / 9);
    EXPECT_EQ(sk.ringWidths().size(), 9u);
    Skeleton back = parseSkeleton(skeletonToJson(sk, {}), "tree.json");
    EXPECT_EQ(back.segments().size(), sk.segments().size());
}

/// kQsm as a CSV with a header, end points and no branch column, cylinders numbered from
/// `firstId`: from 1 as TreeQSM (no parent = 0), or from 0 as other tools export (no parent,
/// no extension = -1, the radius column called radius_cyl).
std::string qsmAsCsv(int firstId) {
    std::string csv =
        fmt::format("ID,parent,extension,{},start_x,start_y,start_z,end_x,end_y,end_z\n",
                    firstId == 0 ? "radius_cyl" : "radius");
    std::istringstream in(kQsm);
    std::string line;
    int id = firstId;
    while (std::getline(in, line)) {
        double v[15];
        std::istringstream cells(line);
        for (double& x : v) cells >> x;
        Vec3 s{v[2], v[3], v[4]}, e = s + normalize(Vec3{v[5], v[6], v[7]}) * v[1];
        const double shift = 1 - firstId;  // TreeQSM numbers are 1-based
        csv += fmt::format("{},{},{},{},{},{},{},{},{},{}\n", id++, v[8] - shift, v[9] - shift,
                           v[0], s.x, s.y, s.z, e.x, e.y, e.z);
    }
    return csv;
}

TEST(QsmImport, HeaderCsvWithEndPointsAndDerivedBranchesGivesTheSameTree) {
    QsmTree ref = parseQsm(kQsm, "tree.txt");
    // Same cylinders as CSV with end points and no branch column.
    QsmTree t = parseQsm(qsmAsCsv(1), "tree.csv");
    ASSERT_EQ(t.skeleton.segments().size(), ref.skeleton.segments().size());
    for (size_t i = 0; i < t.skeleton.nodes().size(); ++i)
        EXPECT_NEAR(length(t.skeleton.node(i).position - ref.skeleton.node(i).position), 0, 1e-12);
    for (size_t i = 0; i < t.skeleton.segments().size(); ++i)
        EXPECT_EQ(t.skeleton.segment(i).parent, ref.skeleton.segment(i).parent);
}

TEST(QsmImport, ZeroBasedExportsWithOtherColumnNamesImport) {
    // Exports of other tools (SimpleForest, R packages converting QSMs) number cylinders from
    // 0, give the stem base parent -1 (and "no extension" -1) and call the radius radius_cyl:
    // once refused.
    QsmTree ref = parseQsm(kQsm, "tree.txt");
    QsmTree t = parseQsm(qsmAsCsv(0), "zero-based.csv");
    ASSERT_EQ(t.skeleton.segments().size(), ref.skeleton.segments().size());
    for (size_t i = 0; i < t.skeleton.segments().size(); ++i)
        EXPECT_EQ(t.skeleton.segment(i).parent, ref.skeleton.segment(i).parent);
    EXPECT_DOUBLE_EQ(t.skeleton.node(0).radius, 0.20);
}

TEST(QsmImport, SegmentExportsTakeTheirChainsFromSegmentsNotBranchIds) {
    // The shape of rTwig's and SimpleForest's QSM.csv, written here from their column list:
    // branchID groups a first-order branch with everything on it, forks included (once
    // refused: "branch 1 forks here"); the chains come from the segments, and at a fork the
    // child segment of the parent's branch order carries the branch on.
    const std::string header =
        "ID,parentID,startX,startY,startZ,endX,endY,endZ,radius,length,growthLength,"
        "averagePointDistance,segmentID,parentSegmentID,branchOrder,reverseBranchOrder,"
        "branchID\n";
    // ID parent  start        end          radius len  gl  apd seg pseg order rbo branch
    const std::string rows =
        "0,-1,0,0,0,0,0,1,0.20,1,9,0.01,0,-1,0,3,0\n"
        "1,0,0,0,1,0,0,2,0.19,1,8,0.01,0,-1,0,3,0\n"
        "2,1,0,0,2,0,0,3,0.18,1,7,0.01,0,-1,0,3,0\n"
        "3,2,0,0,3,0,0,4,0.16,1,3,0.01,1,0,0,1,0\n"  // the stem goes on: segment 1
        "4,3,0,0,4,0,0,5,0.14,1,2,0.01,1,0,0,1,0\n"
        "5,4,0,0,5,0,0,6,0.12,1,1,0.01,1,0,0,1,0\n"
        "6,2,0,0,3,0.5,0,3.5,0.06,0.7,3,0.01,2,0,1,2,1\n"  // a side branch: segment 2
        "7,6,0.5,0,3.5,1,0,4,0.05,0.7,2,0.01,2,0,1,2,1\n"
        "8,7,1,0,4,1.5,0,4.5,0.04,0.7,1,0.01,3,2,1,1,1\n"  // it goes on: segment 3
        "9,7,1,0,4,1,0.5,4.5,0.03,0.7,1,0.01,4,2,2,1,1\n"  // a twig of order 2: segment 4
        "10,9,1,0.5,4.5,1,1,5,0.02,0.7,1,0.01,4,2,2,1,1\n";
    QsmTree t = parseQsm(header + rows, "QSM.csv");
    const Skeleton& sk = t.skeleton;
    EXPECT_EQ(t.cylinders, 11u);
    ASSERT_EQ(sk.chains().size(), 3u);
    EXPECT_EQ(sk.chain(0).segmentCount, 6u);  // the stem, across the fork
    EXPECT_EQ(sk.chain(1).segmentCount, 3u);  // the side branch, across its fork
    EXPECT_EQ(sk.chain(2).segmentCount, 2u);  // the twig
    EXPECT_EQ(sk.chain(1).parentChain, 0);
    EXPECT_EQ(sk.chain(2).parentChain, 1);
    EXPECT_EQ(sk.chain(2).order, 2);
    EXPECT_DOUBLE_EQ(sk.node(0).radius, 0.20);
}

std::string qsmError(const std::string& text) {
    try {
        parseQsm(text, "bad.txt");
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

TEST(QsmImport, BadFilesSayWhereAndWhat) {
    EXPECT_NE(qsmError("0.2\t1\t0\t0\t0\t0\t0\t1\t9\t0\t1\n").find("line 1"), std::string::npos);
    EXPECT_NE(qsmError("0.2\t1\t0\t0\t0\t0\t0\t1\t9\t0\t1\n").find("parent cylinder 9"),
              std::string::npos);
    EXPECT_NE(qsmError("0.2\t1\t0\t0\t0\t0\t0\t1\t0\t0\t1\n0.2\t1\tx\t0\t1\t0\t0\t1\t1\t0\t1\n")
                  .find("line 2"),
              std::string::npos);
    EXPECT_NE(qsmError("0.2\t1\t0\t0\t0\t0\t0\t1\t0\t0\t1\n0.2\t1\t0\t0\t1\t0\t0\t1\t0\t0\t1\n")
                  .find("second cylinder without parent"),
              std::string::npos);
    EXPECT_NE(qsmError("-0.2\t1\t0\t0\t0\t0\t0\t1\t0\t0\t1\n").find("expected at least"),
              std::string::npos);
    // Found by fuzzing: a 1e-303 m stem gave rings so thin that the growth time overflowed.
    EXPECT_NE(qsmError("1e-303\t1\t0\t0\t0\t0\t0\t1\t0\t0\t1\n")
                  .find("radius 1e-303 m: "
                        "expected at least 0.0001 m"),
              std::string::npos);
    EXPECT_NE(qsmError("2e-4\t4000\t0\t0\t0\t0\t0\t1\t0\t0\t1\n").find("rings 2.5e-08 m wide"),
              std::string::npos);
    EXPECT_NE(qsmError("radius,length\n1,2\n").find("start x/y/z"), std::string::npos);
    EXPECT_NE(qsmError("").find("empty"), std::string::npos);
    // A parent number too large for any file: said as it was written, not as a wrapped integer.
    EXPECT_NE(qsmError("0.2\t1\t0\t0\t0\t0\t0\t1\t1e30\t0\t1\n").find("found 1e+30"),
              std::string::npos);
    // A branch that forks into two cylinders of the same branch id.
    EXPECT_NE(qsmError("0.2\t1\t0\t0\t0\t0\t0\t1\t0\t0\t1\n"
                       "0.1\t1\t0\t0\t1\t0\t0\t1\t1\t0\t1\n"
                       "0.1\t1\t0\t0\t1\t1\t0\t0\t1\t0\t1\n")
                  .find("forks"),
              std::string::npos);
    EXPECT_THROW(importQsm("/nonexistent.txt"), InputError);
    // Bounds: a cylinder 1e10 m away once asked for one ring width per year of 2e10 years.
    EXPECT_NE(qsmError("0.2\t1\t0\t0\t1e10\t0\t0\t1\t0\t0\t1\n").find("±1e+07 m"),
              std::string::npos);
    EXPECT_NE(qsmError("200\t1\t0\t0\t0\t0\t0\t1\t0\t0\t1\n").find("millimetres"),
              std::string::npos);
    EXPECT_NE(qsmError("0.2\t9e6\t0\t0\t0\t0\t0\t1\t0\t0\t1\n").find("years old"),
              std::string::npos);
    // Found by fuzzing: a line of other white space (a form feed) once indexed an empty row.
    EXPECT_NE(qsmError("\f\n").find("empty"), std::string::npos);
    EXPECT_EQ(parseQsm("\f\v\n0.2\t1\t0\t0\t0\t0\t0\t1\t0\t0\t1\n", "t.txt").cylinders, 1u);
}

}  // namespace
}  // namespace nenrin
