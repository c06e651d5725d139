#include "skeleton/sources/kanayama/kanayama_growth.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>

#include "skeleton/sources/kanayama/kanayama_hormone.h"
#include "skeleton/sources/kanayama/kanayama_light.h"
#include "skeleton/sources/kanayama/kanayama_skeleton.h"
#include "util/hash.h"

namespace nenrin {

namespace {

constexpr Vec3 kUp{0, 0, 1};

// Random channels: every draw is uniform01(seed, shoot id, channel), so a shoot's draws do not
// depend on how many other draws happened before it.
enum Channel : uint64_t { kJitterAngle = 1, kJitterAzimuth, kDeath, kPhase, kBudRounding };

/// Rodrigues rotation of v about the unit axis.
Vec3 rotateAbout(const Vec3& v, const Vec3& axis, double angle) {
    double c = std::cos(angle), s = std::sin(angle);
    return v * c + cross(axis, v) * s + axis * (dot(axis, v) * (1 - c));
}

/// Unit vector perpendicular to t at `azimuth` around it, measured from the horizontal side
/// (so phyllotaxis is continuous along a shoot that stays away from vertical).
Vec3 sideDirection(const Vec3& t, double azimuth) {
    Vec3 ref = cross(t, kUp);
    ref = lengthSquared(ref) > 1e-12 ? normalize(ref) : anyPerpendicular(t);
    return rotateAbout(ref, t, azimuth);
}

int stochasticRound(double x, double u) { return static_cast<int>(std::floor(x + u)); }

struct Bud {
    int32_t shoot = 0;
    int node = 0;
    Vec3 direction;
    bool terminal = false;  // continues the parent's axis
    int yearFormed = 0;
    bool breakNext = false;
    bool alive = true;
};

struct ShootShape {
    int nodes;
    double internode;
    bool isLong;
};

class Simulation {
public:
    explicit Simulation(const KanayamaOptions& options)
        : o_(options),
          s_(options.species),
          hRef_(s_.production / (1 - s_.beta * s_.alphaTerminal)),
          dome_(makeSkyDome(options.skyDirections)) {
        if (!o_.referenceLight) tracer_ = std::make_unique<LeafLightTracer>();
        light_.extinction = s_.extinction;
        light_.brightness = o_.skyBrightness;
        light_.threads = o_.threads;
    }

    void step(int year) {
        aliveLastYear_.resize(shoots_.size());
        for (size_t i = 0; i < shoots_.size(); ++i) aliveLastYear_[i] = shoots_[i].alive;
        if (year == o_.removeLeaderAtYear) removeLeader(year);
        size_t firstNew = shoots_.size();
        breakBuds(year);
        computeLightAndDeaths(year, firstNew);
        std::vector<double> hormone = transport(firstNew);
        elongate(firstNew, hormone);
        thicken(firstNew);
        formBuds(year, firstNew);
        releaseDormantBuds(year, firstNew, hormone);
        for (size_t i = 0; i < shoots_.size(); ++i)
            if (shoots_[i].alive) shoots_[i].hormone = hormone[i];
        recordYear(firstNew);
    }

    KanayamaTree finish() {
        KanayamaTree tree;
        tree.skeleton = buildKanayamaSkeleton(shoots_, stats_.trunkBaseRadiusPerYear, s_);
        tree.stats = std::move(stats_);
        tree.shoots = std::move(shoots_);
        return tree;
    }

private:
    double u(size_t shoot, Channel c) const { return uniform01(o_.seed, shoot, c); }

    // Above the long-shoot threshold both node count and internode length rise with the square
    // root of the excess vigour, so a shoot's length rises about linearly with its vigour.
    ShootShape shape(double vigour) const {
        if (vigour < s_.longShootVigour) return {s_.shortShootNodes, s_.shortInternode, false};
        double f =
            std::sqrt(std::min((vigour - s_.longShootVigour) / (1 - s_.longShootVigour), 2.0));
        int nodes = s_.shortShootNodes +
                    static_cast<int>(std::lround((s_.longShootMaxNodes - s_.shortShootNodes) * f));
        double internode =
            s_.shortInternode + (s_.longInternodeMax - s_.shortInternode) * std::min(f, 1.0);
        return {std::max(nodes, 1), internode, true};
    }

    double vigourOf(double hormone) const { return std::min(hormone / hRef_, s_.maxVigour); }

    // Leader removal: the main stem's newest `removeLeaderShoots` yearly shoots and everything
    // on them are cut away (a heading cut; the seedling shoot always stays).
    void removeLeader(int year) {
        if (shoots_.empty()) return;
        std::vector<int32_t> stem{0};
        while (continuation_[stem.back()] != kNone && !shoots_[continuation_[stem.back()]].removed)
            stem.push_back(continuation_[stem.back()]);
        size_t keep =
            std::max<size_t>(1, stem.size() - std::min<size_t>(stem.size(), o_.removeLeaderShoots));
        if (keep >= stem.size()) return;
        int32_t cutFrom = stem[keep];
        for (size_t i = cutFrom; i < shoots_.size(); ++i) {
            KanayamaShoot& sh = shoots_[i];
            bool cut = static_cast<int32_t>(i) == cutFrom ||
                       (sh.parent >= 0 && shoots_[sh.parent].removed);
            if (!cut) continue;
            sh.removed = true;
            if (sh.alive) sh.deathTime = year;
            sh.alive = false;
        }
    }

    void addShoot(int year, int32_t parent, int parentNode, const Vec3& start, Vec3 direction,
                  bool terminal, bool fromDormant, double inherited) {
        size_t id = shoots_.size();
        // Seeded wobble: a small tilt in a random azimuth.
        double tilt = s_.directionJitter * u(id, kJitterAngle);
        direction = normalize(rotateAbout(
            direction, sideDirection(direction, 2 * std::numbers::pi * u(id, kJitterAzimuth)),
            tilt));
        KanayamaShoot sh;
        sh.parent = parent;
        sh.parentNode = parentNode;
        sh.year = year;
        sh.terminal = terminal;
        sh.fromDormantBud = fromDormant;
        sh.deathThreshold = s_.deathLight * (1 + s_.deathJitter * (2 * u(id, kDeath) - 1));
        // Step 1 of the year: the provisional shoot the light is computed on, as if fully lit.
        ShootShape provisional = shape(vigourOf(s_.beta * inherited + s_.production));
        sh.nodes.push_back(start);
        for (int i = 1; i <= provisional.nodes; ++i)
            sh.nodes.push_back(start + direction * (provisional.internode * i));
        sh.length = provisional.nodes * provisional.internode;
        sh.leaves = provisional.nodes * s_.leavesPerNode;
        sh.area = s_.initialArea;
        shoots_.push_back(std::move(sh));
        startDirection_.push_back(direction);
        inherited_.push_back(inherited);
        continuation_.push_back(kNone);
        budsOf_.push_back({0, 0});
        if (terminal && parent >= 0) continuation_[parent] = static_cast<int32_t>(id);
        if (fromDormant) ++stats_.dormantBudsBroken;
    }

    void breakBuds(int year) {
        if (year == 0) {
            addShoot(0, kNone, 0, Vec3{}, kUp, true, false, s_.seedlingVigour * hRef_);
            return;
        }
        for (Bud& b : buds_) {
            if (!b.alive || !b.breakNext) continue;
            b.alive = false;
            const KanayamaShoot& parent = shoots_[b.shoot];
            if (!parent.alive) continue;
            addShoot(
                year, b.shoot, b.node, parent.nodes[b.node], b.direction, b.terminal,
                year - b.yearFormed > 1,
                inheritedHormone(parent.hormone, b.terminal, s_.alphaTerminal, s_.alphaLateral));
        }
    }

    // Leaves carried by each shoot and everything above it (children come after parents).
    std::vector<double> leavesAbove(size_t firstNew) const {
        std::vector<double> above(shoots_.size(), 0.0);
        for (size_t i = shoots_.size(); i-- > 0;) {
            const KanayamaShoot& sh = shoots_[i];
            if (!sh.alive) continue;
            if (i >= firstNew) above[i] += sh.leaves;
            if (sh.parent >= 0) above[sh.parent] += above[i];
        }
        return above;
    }

    void computeLightAndDeaths(int year, size_t firstNew) {
        std::vector<LeafSphere> spheres;
        std::vector<size_t> owner;
        for (size_t i = firstNew; i < shoots_.size(); ++i) {
            const KanayamaShoot& sh = shoots_[i];
            if (!sh.alive) continue;
            spheres.push_back(
                {(sh.nodes.front() + sh.nodes.back()) * 0.5, s_.leafSize + 0.5 * sh.length});
            owner.push_back(i);
        }
        auto t0 = std::chrono::steady_clock::now();
        std::vector<SphereLight> light = tracer_ ? tracer_->compute(spheres, dome_, light_)
                                                 : leafLightReference(spheres, dome_, light_);
        stats_.lightSeconds +=
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        brightest_.assign(shoots_.size(), kUp);
        for (size_t k = 0; k < owner.size(); ++k) {
            KanayamaShoot& sh = shoots_[owner[k]];
            sh.light = light[k].light;
            brightest_[owner[k]] = light[k].brightestDirection;
            if (sh.light < sh.deathThreshold) {
                sh.alive = false;
                sh.deathTime = year + s_.seasonFraction;
                ++stats_.shootDeaths;
            }
        }
        // An older shoot with no living leaves above it has nothing to live on.
        std::vector<double> above = leavesAbove(firstNew);
        for (size_t i = 0; i < firstNew; ++i) {
            KanayamaShoot& sh = shoots_[i];
            if (sh.alive && above[i] <= 0) {
                sh.alive = false;
                sh.deathTime = year;
                ++stats_.branchDeaths;
            }
        }
    }

    std::vector<double> transport(size_t firstNew) const {
        size_t n = shoots_.size();
        std::vector<int32_t> parent(n);
        std::vector<double> previous(n), production(n, 0.0);
        std::vector<uint8_t> alive(n);
        for (size_t i = 0; i < n; ++i) {
            const KanayamaShoot& sh = shoots_[i];
            parent[i] = sh.parent;
            alive[i] = sh.alive ? 1 : 0;
            previous[i] = i >= firstNew ? inherited_[i] : sh.hormone;
            if (i >= firstNew) production[i] = sh.light * s_.production;
        }
        return transportHormone(parent, previous, production, alive, s_.beta, s_.gamma);
    }

    // Step 4: the real shoot, its length and bending set by its hormone.
    void elongate(size_t firstNew, const std::vector<double>& hormone) {
        for (size_t i = firstNew; i < shoots_.size(); ++i) {
            KanayamaShoot& sh = shoots_[i];
            if (!sh.alive) continue;
            sh.vigour = vigourOf(hormone[i]);
            ShootShape sp = shape(sh.vigour);
            sh.longShoot = sp.isLong;
            Vec3 pull = (kUp * s_.gravitropism + brightest_[i] * s_.phototropism) * sh.vigour;
            Vec3 d = startDirection_[i], p = sh.nodes.front();
            sh.nodes.resize(1);
            for (int k = 1; k <= sp.nodes; ++k) {
                Vec3 bent = d + pull;
                if (lengthSquared(bent) > 1e-12) d = normalize(bent);
                p += d * sp.internode;
                sh.nodes.push_back(p);
            }
            sh.length = sp.nodes * sp.internode;
            sh.leaves = sp.nodes * s_.leavesPerNode;
        }
    }

    void thicken(size_t firstNew) {
        std::vector<double> above = leavesAbove(firstNew);
        for (size_t i = 0; i < shoots_.size(); ++i) {
            KanayamaShoot& sh = shoots_[i];
            if (sh.alive) sh.area += s_.areaPerLeaf * above[i];
        }
    }

    void addBud(int32_t shoot, int node, const Vec3& direction, bool terminal, int year,
                bool breakNext) {
        buds_.push_back({shoot, node, direction, terminal, year, breakNext, true});
    }

    void formBuds(int year, size_t firstNew) {
        double ageFactor = std::min(1.0, s_.budBreakAgeStart + s_.budBreakAgeRate * year);
        for (size_t i = firstNew; i < shoots_.size(); ++i) {
            const KanayamaShoot& sh = shoots_[i];
            if (!sh.alive) continue;
            auto id = static_cast<int32_t>(i);
            int m = static_cast<int>(sh.nodes.size()) - 1;
            double phase = 2 * std::numbers::pi * u(i, kPhase);
            auto tangent = [&](int node) { return normalize(sh.nodes[node] - sh.nodes[node - 1]); };
            auto lateral = [&](int node, double azimuth, double angle) {
                Vec3 t = tangent(node);
                return normalize(t * std::cos(angle) + sideDirection(t, azimuth) * std::sin(angle));
            };
            size_t firstBud = buds_.size();
            Vec3 tip = tangent(m);
            double tipAzimuth = phase + s_.phyllotaxis * m;
            int tl = s_.terminalLateralBuds;
            if (s_.branching == KanayamaBranching::Monopodial) {
                addBud(id, m, tip, true, year, true);
            } else if (tl > 0) {
                // Sympodial: the terminal bud aborts; the first terminal-lateral bud takes over
                // the axis, bent at the node.
                addBud(id, m, lateral(m, tipAzimuth, s_.sympodialBend), true, year, true);
            }
            int firstTl = s_.branching == KanayamaBranching::Monopodial ? 0 : 1;
            for (int j = firstTl; j < tl; ++j)
                addBud(id, m,
                       lateral(m, tipAzimuth + 2 * std::numbers::pi * j / tl, s_.lateralAngle),
                       false, year, sh.longShoot);
            // Axillary buds, upper ones first (acrotony): the vigour decides how many break.
            int breaking = sh.longShoot ? stochasticRound(s_.budBreak * sh.vigour * ageFactor,
                                                          u(i, kBudRounding))
                                        : 0;
            int perNode = s_.lateralBudsPerNode;
            for (int node = m - 1; node >= 1; --node)
                for (int j = 0; j < perNode; ++j) {
                    double az = phase + s_.phyllotaxis * node + 2 * std::numbers::pi * j / perNode;
                    addBud(id, node, lateral(node, az, s_.lateralAngle), false, year,
                           breaking-- > 0);
                }
            budsOf_[i] = {firstBud, buds_.size()};
        }
    }

    // Dormant buds break on an old shoot whose hormone is high, or when the hormone sent down
    // to it fell sharply because a branch above was lost (death, pruning, leader removal):
    // the lost children's last-year hormone exceeds (1 - dormantDropRatio) of what all its
    // children sent last year. (Comparing totals year to year would miss it: in a growing
    // tree the hormone from the rest of the crown keeps rising.)
    void releaseDormantBuds(int year, size_t firstNew, const std::vector<double>& hormone) {
        std::vector<double> inflow(shoots_.size(), 0.0), lost(shoots_.size(), 0.0);
        for (size_t i = shoots_.size(); i-- > 1;) {
            const KanayamaShoot& sh = shoots_[i];
            if (sh.parent < 0) continue;
            if (sh.alive) inflow[sh.parent] += hormone[i];
            if (i < firstNew && aliveLastYear_[i] && !sh.alive) lost[sh.parent] += sh.hormone;
        }
        inflow_.resize(shoots_.size(), 0.0);
        for (size_t i = 0; i < firstNew; ++i) {
            const KanayamaShoot& sh = shoots_[i];
            if (!sh.alive) continue;
            bool high = hormone[i] > s_.dormantBreakVigour * hRef_;
            bool drop = lost[i] > 0 && lost[i] > (1 - s_.dormantDropRatio) * inflow_[i];
            auto [begin, end] = budsOf_[i];
            int released = 0;
            for (size_t b = end; b-- > begin;) {
                Bud& bud = buds_[b];
                if (!bud.alive || bud.breakNext) continue;
                if (year - bud.yearFormed > s_.dormantLifetime) {
                    bud.alive = false;
                    continue;
                }
                if ((high || drop) && released < s_.dormantBreakCount) {
                    bud.breakNext = true;
                    ++released;
                }
            }
        }
        inflow_ = std::move(inflow);
    }

    void recordYear(size_t firstNew) {
        double height = 0;
        for (const KanayamaShoot& sh : shoots_)
            if (sh.alive)
                for (const Vec3& p : sh.nodes) height = std::max(height, p.z);
        stats_.heightPerYear.push_back(height);
        stats_.newShootsPerYear.push_back(static_cast<int>(shoots_.size() - firstNew));
        stats_.trunkBaseRadiusPerYear.push_back(std::sqrt(shoots_[0].area / std::numbers::pi));
    }

    const KanayamaOptions& o_;
    const KanayamaSpecies& s_;
    double hRef_;
    SkyDome dome_;
    LeafLightParameters light_;
    std::unique_ptr<LeafLightTracer> tracer_;

    std::vector<KanayamaShoot> shoots_;
    std::vector<Vec3> startDirection_;
    std::vector<double> inherited_;
    std::vector<int32_t> continuation_;
    std::vector<std::pair<size_t, size_t>> budsOf_;
    std::vector<Vec3> brightest_;
    std::vector<double> inflow_;
    std::vector<uint8_t> aliveLastYear_;  // hormone each shoot received from its children last year
    std::vector<Bud> buds_;
    KanayamaStats stats_;
};

}  // namespace

KanayamaTree growKanayamaTree(const KanayamaOptions& options,
                              const std::function<void(int year, int years)>& progress) {
    validateKanayamaOptions(options);
    Simulation sim(options);
    for (int year = 0; year < options.years; ++year) {
        sim.step(year);
        if (progress) progress(year, options.years);
    }
    return sim.finish();
}

}  // namespace nenrin
