#include "skeleton/sources/measured/qsm_import.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include "skeleton/segment_geometry.h"
#include "util/input_error.h"
#include "util/input_file.h"
#include "util/limits.h"

namespace nenrin {

namespace {

/// Points closer than this are one point (QSM cylinders often start where the last ended).
constexpr double kSamePoint = 1e-6;
// Bounds of a plausible scanned tree: projected coordinates (UTM northings < 1e7 m), the
// thickest trunks (a few metres), and the oldest trees (~5000 years; one entry per year).
constexpr double kMaxQsmCoordinate = 1e7;
constexpr double kMaxQsmRadius = 50;
// Scanners resolve no twig thinner than a millimetre; a 0.1 mm radius is surely a unit error.
constexpr double kMinQsmRadius = 1e-4;
constexpr double kMaxQsmAge = 10000;
// A TreeQSM text export is ~150 bytes per cylinder: a million cylinders.
constexpr uintmax_t kMaxQsmFileBytes = uintmax_t(256) << 20;

enum Column {
    Id,
    Radius,
    Length,
    SX,
    SY,
    SZ,
    AX,
    AY,
    AZ,
    EX,
    EY,
    EZ,
    Parent,
    Extension,
    Branch,
    Segment,      ///< SimpleForest / rTwig: a run of cylinders between forks
    BranchOrder,  ///< 0 the stem, 1 its branches, ...
    ColumnCount
};

/// Header names (lower case, letters and digits only) for each column.
const std::map<std::string, Column>& headerNames() {
    static const std::map<std::string, Column> names = {{"id", Id},
                                                        {"cylinder", Id},
                                                        {"cylinderid", Id},
                                                        {"cylid", Id},
                                                        {"radius", Radius},
                                                        {"rad", Radius},
                                                        {"radiusm", Radius},
                                                        {"radiuscyl", Radius},
                                                        {"cylradius", Radius},
                                                        {"cylinderradius", Radius},
                                                        {"r", Radius},
                                                        {"length", Length},
                                                        {"len", Length},
                                                        {"startx", SX},
                                                        {"starty", SY},
                                                        {"startz", SZ},
                                                        {"startpointx", SX},
                                                        {"startpointy", SY},
                                                        {"startpointz", SZ},
                                                        {"sx", SX},
                                                        {"sy", SY},
                                                        {"sz", SZ},
                                                        {"axisx", AX},
                                                        {"axisy", AY},
                                                        {"axisz", AZ},
                                                        {"axisdirectionx", AX},
                                                        {"axisdirectiony", AY},
                                                        {"axisdirectionz", AZ},
                                                        {"axx", AX},
                                                        {"axy", AY},
                                                        {"axz", AZ},
                                                        {"endx", EX},
                                                        {"endy", EY},
                                                        {"endz", EZ},
                                                        {"endpointx", EX},
                                                        {"endpointy", EY},
                                                        {"endpointz", EZ},
                                                        {"ex", EX},
                                                        {"ey", EY},
                                                        {"ez", EZ},
                                                        {"parent", Parent},
                                                        {"parentid", Parent},
                                                        {"cpar", Parent},
                                                        {"parentcylinder", Parent},
                                                        {"extension", Extension},
                                                        {"extensionid", Extension},
                                                        {"cext", Extension},
                                                        {"next", Extension},
                                                        {"branch", Branch},
                                                        {"branchid", Branch},
                                                        {"boc1", Branch},
                                                        {"segmentid", Segment},
                                                        {"segment", Segment},
                                                        {"branchorder", BranchOrder}};
    return names;
}

struct Cylinder {
    long long id = 0, parent = 0, extension = 0, branch = 0;
    long long segment = -1, order = -1;  ///< -1: the file has no such column
    double radius = 0;
    Vec3 start, end;
    size_t line = 0;
};

std::vector<std::string> splitRow(const std::string& line) {
    std::vector<std::string> cells;
    char sep = line.find('\t') != std::string::npos  ? '\t'
               : line.find(',') != std::string::npos ? ','
                                                     : ' ';
    std::string cell;
    std::istringstream in(line);
    if (sep == ' ') {
        while (in >> cell) cells.push_back(cell);
        return cells;
    }
    while (std::getline(in, cell, sep)) {
        auto b = cell.find_first_not_of(" \r\"");
        auto e = cell.find_last_not_of(" \r\"");
        cells.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
    }
    return cells;
}

std::string normalise(const std::string& name) {
    std::string out;
    for (char c : name)
        if (std::isalnum(static_cast<unsigned char>(c)))
            out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

bool looksNumeric(const std::string& cell) {
    char* end = nullptr;
    std::strtod(cell.c_str(), &end);
    return !cell.empty() && end && *end == '\0';
}

class QsmReader {
public:
    QsmReader(std::string name, const QsmOptions& options) : name_(std::move(name)), o_(options) {}

    QsmTree read(const std::string& text) {
        if (!(o_.elongationSpeed > 0) || !std::isfinite(o_.elongationSpeed))
            throw InputError(name_, "", "expected an elongation speed > 0 m/year");
        readRows(text);
        if (cylinders_.empty()) throw InputError(name_, "", "no cylinders: the file is empty");
        linkCylinders();
        return build();
    }

private:
    InputError lineError(size_t line, const std::string& message) const {
        return InputError(name_, fmt::format("line {}", line), message);
    }

    void readRows(const std::string& text) {
        std::istringstream in(text);
        std::string line;
        size_t lineNo = 0;
        bool first = true;
        while (std::getline(in, line)) {
            ++lineNo;
            auto b = line.find_first_not_of(" \t\r\f\v");
            if (b == std::string::npos || line[b] == '#' || line[b] == '%') continue;
            std::vector<std::string> cells = splitRow(line);
            if (cells.empty()) continue;  // only separators and other white space
            if (first) {
                first = false;
                if (!looksNumeric(cells[0])) {
                    readHeader(cells, lineNo);
                    continue;
                }
                useTreeQsmColumns(cells.size(), lineNo);
            }
            readCylinder(cells, lineNo);
        }
    }

    /// TreeQSM's save_model_text: radius, length, start xyz, axis xyz, parent, extension,
    /// branch, then columns nenrin does not need (order, position, mad, SurfCov, added, ...).
    void useTreeQsmColumns(size_t count, size_t line) {
        if (count < 11)
            throw lineError(line, fmt::format("found {} columns: expected TreeQSM's cylinder "
                                              "columns (radius, length, start x y z, axis x y z, "
                                              "parent, extension, branch, ...) or a header row",
                                              count));
        column_.fill(-1);
        int index = 0;
        for (Column c : {Radius, Length, SX, SY, SZ, AX, AY, AZ, Parent, Extension, Branch})
            column_[c] = index++;
    }

    void readHeader(const std::vector<std::string>& cells, size_t line) {
        column_.fill(-1);
        for (size_t i = 0; i < cells.size(); ++i) {
            auto it = headerNames().find(normalise(cells[i]));
            if (it != headerNames().end() && column_[it->second] < 0)
                column_[it->second] = static_cast<int>(i);
        }
        auto need = [&](std::initializer_list<Column> cols, const char* what) {
            for (Column c : cols)
                if (column_[c] < 0)
                    throw lineError(line, fmt::format("the header has no {} column (see "
                                                      "docs/trees.md for accepted names)",
                                                      what));
        };
        need({Radius}, "radius");
        need({SX, SY, SZ}, "start x/y/z");
        need({Parent}, "parent");
        bool axis =
            column_[AX] >= 0 && column_[AY] >= 0 && column_[AZ] >= 0 && column_[Length] >= 0;
        bool end = column_[EX] >= 0 && column_[EY] >= 0 && column_[EZ] >= 0;
        if (!axis && !end)
            throw lineError(line, "the header needs either axis x/y/z with length, or end x/y/z");
        if (axis && end) column_[EX] = column_[EY] = column_[EZ] = -1;  // axis + length wins
        // With segments (SimpleForest, rTwig's QSM.csv), branchID groups a first-order branch
        // with everything on it, forks included: the chains are made from the segments.
        if (column_[Segment] >= 0) column_[Branch] = -1;
    }

    double number(const std::vector<std::string>& cells, Column c, size_t line) const {
        size_t i = static_cast<size_t>(column_[c]);
        if (i >= cells.size())
            throw lineError(
                line, fmt::format("found {} columns, expected at least {}", cells.size(), i + 1));
        char* end = nullptr;
        double v = std::strtod(cells[i].c_str(), &end);
        if (cells[i].empty() || *end != '\0' || !std::isfinite(v))
            throw lineError(
                line, fmt::format("column {}: \"{}\" is not a finite number", i + 1, cells[i]));
        return v;
    }

    /// A cylinder or branch number: a whole number >= 0, or -1 for "none" (exports with
    /// 0-based numbers mark the stem base's parent and a missing extension so).
    long long integer(const std::vector<std::string>& cells, Column c, size_t line) const {
        double v = number(cells, c, line);
        if (v != std::floor(v) || v < -1 || v > 1e15)
            throw lineError(line, fmt::format("column {}: expected a cylinder/branch number "
                                              "(a whole number >= 0, or -1 for none), found {:g}",
                                              column_[c] + 1, v));
        return static_cast<long long>(v);
    }

    void readCylinder(const std::vector<std::string>& cells, size_t line) {
        Cylinder cyl;
        cyl.line = line;
        cyl.id = column_[Id] >= 0 ? integer(cells, Id, line)
                                  : static_cast<long long>(cylinders_.size() + 1);
        if (cyl.id < 0)
            throw lineError(line,
                            fmt::format("cylinder number {}: expected a number >= 0", cyl.id));
        cyl.radius = number(cells, Radius, line);
        if (!(cyl.radius >= kMinQsmRadius))
            throw lineError(line, fmt::format("radius {:g} m: expected at least {:g} m (0.1 mm)",
                                              cyl.radius, kMinQsmRadius));
        if (cyl.radius > kMaxQsmRadius)
            throw lineError(line, fmt::format("radius {:g} m: expected at most {:g} m (is the file "
                                              "in millimetres?)",
                                              cyl.radius, kMaxQsmRadius));
        cyl.start = {number(cells, SX, line), number(cells, SY, line), number(cells, SZ, line)};
        if (column_[EX] >= 0) {
            cyl.end = {number(cells, EX, line), number(cells, EY, line), number(cells, EZ, line)};
        } else {
            double len = number(cells, Length, line);
            Vec3 axis{number(cells, AX, line), number(cells, AY, line), number(cells, AZ, line)};
            if (!(len > 0)) throw lineError(line, fmt::format("length {} m: expected > 0", len));
            if (length(axis) < 1e-9) throw lineError(line, "the axis is the zero vector");
            cyl.end = cyl.start + normalize(axis) * len;
        }
        for (const Vec3& p : {cyl.start, cyl.end})
            for (double v : {p.x, p.y, p.z})
                if (std::abs(v) > kMaxQsmCoordinate)
                    throw lineError(line, fmt::format("coordinate {:g} m: expected within "
                                                      "±{:g} m (metres, local or projected)",
                                                      v, kMaxQsmCoordinate));
        if (length(cyl.end - cyl.start) < kSamePoint)
            throw lineError(line, "the cylinder has no length");
        cyl.parent = integer(cells, Parent, line);
        cyl.extension = column_[Extension] >= 0 ? integer(cells, Extension, line) : 0;
        cyl.branch = column_[Branch] >= 0 ? integer(cells, Branch, line) : 0;
        if (column_[Segment] >= 0) cyl.segment = integer(cells, Segment, line);
        if (column_[BranchOrder] >= 0) cyl.order = integer(cells, BranchOrder, line);
        if (!index_.emplace(cyl.id, cylinders_.size()).second)
            throw lineError(line, fmt::format("cylinder {} appears twice", cyl.id));
        cylinders_.push_back(cyl);
    }

    /// Children per cylinder, the root, and a branch id for every cylinder (derived when the
    /// file has no branch column, see continuesBranch).
    void linkCylinders() {
        children_.assign(cylinders_.size(), {});
        std::optional<size_t> root;
        for (size_t i = 0; i < cylinders_.size(); ++i) {
            const Cylinder& c = cylinders_[i];
            // No parent: -1, or 0 where the numbers start at 1 (TreeQSM).
            if (c.parent < 0 || (c.parent == 0 && !index_.count(0))) {
                if (root)
                    throw lineError(c.line, fmt::format("a second cylinder without parent (the "
                                                        "first is on line {}): expected one "
                                                        "tree",
                                                        cylinders_[*root].line));
                root = i;
                continue;
            }
            auto it = index_.find(c.parent);
            if (it == index_.end())
                throw lineError(c.line, fmt::format("parent cylinder {} does not exist", c.parent));
            children_[it->second].push_back(i);
        }
        if (!root) throw InputError(name_, "", "no cylinder without parent: expected a stem base");
        root_ = *root;
        // Breadth-first: every cylinder reached once (a cycle leaves some unreached).
        order_ = {root_};
        for (size_t k = 0; k < order_.size(); ++k)
            for (size_t child : children_[order_[k]]) order_.push_back(child);
        if (order_.size() != cylinders_.size())
            for (size_t i = 0; i < cylinders_.size(); ++i)
                if (std::find(order_.begin(), order_.end(), i) == order_.end())
                    throw lineError(cylinders_[i].line,
                                    "the cylinder is not connected to the stem (a parent cycle)");
        if (column_[Branch] < 0) deriveBranches();
    }

    /// Which child of cylinder `i` carries its branch on: the parent's extension; with
    /// segments, the child in the same segment, else at a fork the first child of the same
    /// branch order (a side branch's order is one more); without either, the first child.
    std::optional<size_t> continuingChild(size_t i) const {
        const Cylinder& parent = cylinders_[i];
        const std::vector<size_t>& kids = children_[i];
        if (kids.empty()) return std::nullopt;
        if (column_[Extension] >= 0) {
            for (size_t k : kids)
                if (cylinders_[k].id == parent.extension) return k;
            return std::nullopt;
        }
        if (column_[Segment] >= 0) {
            for (size_t k : kids)
                if (cylinders_[k].segment == parent.segment) return k;
            if (column_[BranchOrder] >= 0) {
                for (size_t k : kids)
                    if (cylinders_[k].order == parent.order) return k;
                return std::nullopt;
            }
        }
        return kids.front();
    }

    void deriveBranches() {
        long long next = 1;
        cylinders_[root_].branch = next++;
        for (size_t i : order_) {
            const std::optional<size_t> continuing = continuingChild(i);
            for (size_t k : children_[i])
                cylinders_[k].branch = k == continuing ? cylinders_[i].branch : next++;
        }
    }

    /// The cylinders of each branch, base to tip, following parent links.
    std::vector<size_t> branchPath(size_t first) const {
        std::vector<size_t> path{first};
        for (;;) {
            std::optional<size_t> next;
            for (size_t child : children_[path.back()])
                if (cylinders_[child].branch == cylinders_[first].branch) {
                    if (next)
                        throw lineError(cylinders_[child].line,
                                        fmt::format("branch {} forks here: expected each branch "
                                                    "to be one chain of cylinders",
                                                    cylinders_[first].branch));
                    next = child;
                }
            if (!next) return path;
            path.push_back(*next);
        }
    }

    QsmTree build() {
        QsmTree tree;
        tree.cylinders = cylinders_.size();
        // Chains in breadth-first order of their first cylinder: parents come first.
        std::vector<size_t> firsts;
        std::map<long long, size_t> firstOfBranch;
        for (size_t i : order_) {
            const Cylinder& c = cylinders_[i];
            bool startsBranch = i == root_ || cylinders_[index_.at(c.parent)].branch != c.branch;
            if (!startsBranch) continue;
            if (!firstOfBranch.emplace(c.branch, i).second)
                throw lineError(c.line,
                                fmt::format("branch {} starts twice (also on line {})", c.branch,
                                            cylinders_[firstOfBranch[c.branch]].line));
            firsts.push_back(i);
        }
        std::vector<uint32_t> segmentOfCylinder(cylinders_.size(), 0);
        std::vector<std::vector<Vec3>> chainPoints;
        std::vector<std::vector<double>> chainBirths;
        double lastBirth = 0;
        for (size_t first : firsts) {
            std::vector<size_t> path = branchPath(first);
            std::vector<Vec3> points;
            std::vector<double> births, radii;
            std::vector<size_t> pointCylinder;
            uint32_t parentSegment = 0;
            double birth = 0;
            ChainProperties props;
            if (first != root_) {
                // Start on the parent cylinder's segment, at the nearest point of its axis.
                size_t p = index_.at(cylinders_[first].parent);
                parentSegment = segmentOfCylinder[p];
                const Skeleton& sk = tree.skeleton;
                const SkeletonSegment& ps = sk.segment(parentSegment);
                auto pr = projectOntoSegment(cylinders_[first].start, sk.start(ps), sk.end(ps));
                points.push_back(lerp(sk.start(ps), sk.end(ps), pr.t));
                birth = sk.node(ps.from).birthTime +
                        (sk.node(ps.to).birthTime - sk.node(ps.from).birthTime) * pr.t;
                births.push_back(birth);
                radii.push_back(cylinders_[first].radius);
                props.gamma =
                    std::clamp(cylinders_[first].radius / cylinders_[p].radius, 0.05, 2.0);
                props.diebackExponent = o_.diebackExponent;
            }
            auto add = [&](const Vec3& q, double radius) {
                if (!points.empty()) {
                    double step = length(q - points.back());
                    if (step < kSamePoint) return false;
                    birth += step / o_.elongationSpeed;
                }
                points.push_back(q);
                births.push_back(birth);
                radii.push_back(radius);
                return true;
            };
            uint32_t firstSegment = static_cast<uint32_t>(tree.skeleton.segments().size());
            for (size_t c : path) {
                add(cylinders_[c].start, cylinders_[c].radius);
                // Cylinder c lies on the segment that starts at its start point.
                segmentOfCylinder[c] = firstSegment + static_cast<uint32_t>(points.size() - 1);
            }
            add(cylinders_[path.back()].end, cylinders_[path.back()].radius);
            if (points.size() < 2)
                throw lineError(cylinders_[first].line, "the branch has no length");
            for (size_t c : path)
                segmentOfCylinder[c] = std::min<uint32_t>(
                    segmentOfCylinder[c], firstSegment + static_cast<uint32_t>(points.size() - 2));
            if (first == root_)
                tree.skeleton.addTrunk(points, births, radii);
            else
                tree.skeleton.addBranch(parentSegment, points, births, props, radii);
            tree.branchIdOfChain.push_back(cylinders_[first].branch);
            lastBirth = std::max(lastBirth, births.back());
        }
        if (lastBirth > kMaxQsmAge)
            throw InputError(name_, "",
                             fmt::format("the tree would be {:.3g} years old (its longest path "
                                         "at {:g} m/year): expected at most {:g}; check that the "
                                         "file is in metres, or the elongation speed",
                                         lastBirth, o_.elongationSpeed, kMaxQsmAge));
        tree.branches = firsts.size();
        tree.age = std::max(1.0, std::ceil(lastBirth - 1e-9));
        tree.ringWidth = cylinders_[root_].radius / tree.age;
        if (tree.ringWidth < kMinRingWidth)
            throw lineError(
                cylinders_[root_].line,
                fmt::format("the trunk's first cylinder, {:g} m thick after {:g} "
                            "years, gives rings {:.3g} m wide: expected at least {:g} "
                            "m; check the elongation speed",
                            cylinders_[root_].radius, tree.age, tree.ringWidth, kMinRingWidth));
        tree.skeleton.setRingWidths(
            std::vector<double>(static_cast<size_t>(tree.age), tree.ringWidth));
        return tree;
    }

    std::string name_;
    QsmOptions o_;
    std::array<int, ColumnCount> column_{};
    std::vector<Cylinder> cylinders_;
    std::map<long long, size_t> index_;
    std::vector<std::vector<size_t>> children_;
    std::vector<size_t> order_;
    size_t root_ = 0;
};

}  // namespace

QsmTree parseQsm(const std::string& text, const std::string& name, const QsmOptions& options) {
    return QsmReader(name, options).read(text);
}

QsmTree importQsm(const std::string& path, const QsmOptions& options) {
    return parseQsm(readInputFile(path, kMaxQsmFileBytes, "a QSM cylinder list"), path, options);
}

}  // namespace nenrin
