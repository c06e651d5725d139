#include "skeleton/skeleton_writer.h"

#include <cmath>

#include "util/atomic_output.h"
#include "util/input_error.h"

namespace nenrin {

namespace {

nlohmann::json point(const Vec3& p) { return nlohmann::json::array({p.x, p.y, p.z}); }

class SkeletonJsonWriter {
public:
    explicit SkeletonJsonWriter(const Skeleton& skeleton) : sk_(skeleton) {
        children_.resize(sk_.chains().size());
        for (uint32_t c = 1; c < sk_.chains().size(); ++c)
            children_[static_cast<size_t>(sk_.chain(c).parentChain)].push_back(c);
        hasRadii_ = false;
        for (const auto& n : sk_.nodes()) hasRadii_ = hasRadii_ || n.radius > 0;
    }

    nlohmann::json trunk() const {
        nlohmann::json t;
        const SkeletonChain& c = sk_.chain(0);
        nlohmann::json pts = nlohmann::json::array(), births = nlohmann::json::array(),
                       radii = nlohmann::json::array();
        for (uint32_t n : chainNodes(c)) {
            pts.push_back(point(sk_.node(n).position));
            births.push_back(sk_.node(n).birthTime);
            radii.push_back(sk_.node(n).radius);
        }
        t["points"] = pts;
        t["birth_times"] = births;
        if (hasRadii_) t["radii"] = radii;
        return t;
    }

    nlohmann::json branchesOf(uint32_t chain) const {
        nlohmann::json list = nlohmann::json::array();
        for (uint32_t c : children_[chain]) list.push_back(branch(c));
        return list;
    }

private:
    std::vector<uint32_t> chainNodes(const SkeletonChain& c) const {
        std::vector<uint32_t> nodes{sk_.segment(c.firstSegment).from};
        for (uint32_t i = 0; i < c.segmentCount; ++i)
            nodes.push_back(sk_.segment(c.firstSegment + i).to);
        return nodes;
    }

    nlohmann::json branch(uint32_t chain) const {
        const SkeletonChain& c = sk_.chain(chain);
        const SkeletonSegment& first = sk_.segment(c.firstSegment);
        std::vector<uint32_t> nodes = chainNodes(c);
        const SkeletonNode& start = sk_.node(nodes[0]);
        nlohmann::json b;
        b["start"] = point(start.position);
        b["on_segment"] =
            first.parent - static_cast<int32_t>(sk_.chain(c.parentChain).firstSegment);
        b["start_birth_time"] = start.birthTime;
        nlohmann::json pts = nlohmann::json::array(), births = nlohmann::json::array(),
                       radii = nlohmann::json::array();
        for (size_t i = 1; i < nodes.size(); ++i) {
            pts.push_back(point(sk_.node(nodes[i]).position));
            births.push_back(sk_.node(nodes[i]).birthTime);
            radii.push_back(sk_.node(nodes[i]).radius);
        }
        b["points"] = pts;
        b["birth_times"] = births;
        if (hasRadii_) {
            b["start_radius"] = start.radius;
            b["radii"] = radii;
        }
        b["gamma"] = first.gamma;
        if (std::isfinite(first.deathTime)) b["death_time"] = first.deathTime;
        b["dieback_exponent"] = first.diebackExponent;
        if (!children_[chain].empty()) b["branches"] = branchesOf(chain);
        return b;
    }

    const Skeleton& sk_;
    std::vector<std::vector<uint32_t>> children_;
    bool hasRadii_;
};

}  // namespace

nlohmann::json skeletonToJson(const Skeleton& skeleton, const SkeletonFileInfo& info) {
    if (skeleton.empty()) throw std::logic_error("skeletonToJson: empty skeleton");
    SkeletonJsonWriter writer(skeleton);
    nlohmann::json j;
    j["format"] = "nenrin-skeleton";
    if (!info.description.empty()) j["description"] = info.description;
    if (!info.source.empty()) j["source"] = info.source;
    j["trunk"] = writer.trunk();
    j["branches"] = writer.branchesOf(0);
    if (!skeleton.ringWidths().empty()) j["ring_widths"] = skeleton.ringWidths();
    if (!skeleton.latewoodShares().empty()) j["latewood_shares"] = skeleton.latewoodShares();
    return j;
}

void saveSkeletonFile(const Skeleton& skeleton, const SkeletonFileInfo& info,
                      const std::string& path) {
    nlohmann::json j = skeletonToJson(skeleton, info);
    writeTextAtomically(path, j.dump(1) + '\n', "skeleton file");
}

}  // namespace nenrin
