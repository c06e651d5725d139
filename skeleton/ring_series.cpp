#include "skeleton/ring_series.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>

#include "util/input_error.h"
#include "util/input_file.h"

namespace nenrin {

namespace {

constexpr long kMarkerHundredths = 999;     // end of a series in 0.01 mm
constexpr long kMarkerThousandths = -9999;  // end of a series in 0.001 mm
constexpr size_t kMaxFileBytes = size_t(64) << 20;

std::string trim(std::string_view s) {
    size_t a = s.find_first_not_of(" \t\r");
    if (a == std::string_view::npos) return "";
    size_t b = s.find_last_not_of(" \t\r");
    return std::string(s.substr(a, b - a + 1));
}

/// An integer filling a fixed-width field (blanks around it), or nothing.
std::optional<long> fieldInteger(std::string_view field) {
    std::string t = trim(field);
    if (t.empty()) return std::nullopt;
    long v = 0;
    auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (ec != std::errc() || end != t.data() + t.size()) return std::nullopt;
    return v;
}

struct DataLine {
    std::string id;
    long year = 0;
    std::vector<long> values;
};

/// A data line, or nothing when the line is not one (a header line).
std::optional<DataLine> parseDataLine(std::string_view line) {
    if (line.size() < 13) return std::nullopt;
    DataLine d;
    d.id = trim(line.substr(0, 8));
    auto year = fieldInteger(line.substr(8, 4));
    if (d.id.empty() || !year) return std::nullopt;
    d.year = *year;
    for (size_t at = 12; at < line.size(); at += 6) {
        std::string_view field = line.substr(at, 6);
        if (trim(field).empty()) {
            if (!trim(line.substr(at)).empty()) return std::nullopt;  // a gap, then more text
            break;
        }
        auto v = fieldInteger(field);
        if (!v) return std::nullopt;
        d.values.push_back(*v);
    }
    if (d.values.empty() || d.values.size() > 10) return std::nullopt;
    return d;
}

std::string lineAt(int n) { return fmt::format("line {}", n); }

/// A problem of one series at a line: the series is marked, the file read on.
struct SeriesProblem {
    int line;
    std::string message;
};

/// Reads a Tucson file line by line. A series stays open from its first data line until its
/// end marker, a line that stops before its decade's end or the next series' first line.
class TucsonReader {
public:
    explicit TucsonReader(const std::string& path) { file_.path = path; }

    void readLine(const std::string& line) {
        ++lineNo_;
        if (line.find('\0') != std::string::npos)
            throw InputError(file_.path, lineAt(lineNo_), "holds a NUL byte: expected a text file");
        if (trim(line).empty()) return;
        auto d = parseDataLine(line);
        if (!d) {
            readHeaderLine(line);
            return;
        }
        if (open_ && d->id != current_.id) closeSeries(lastDataLine_);
        lastDataLine_ = lineNo_;
        if (open_ && current_.bad()) return;  // the rest of a bad series
        try {
            readSeriesLine(*d);
        } catch (const SeriesProblem& p) {
            markBad(p);
        }
    }

    RingSeriesFile finish() {
        if (open_) closeSeries(lastDataLine_);
        if (file_.series.empty())
            throw InputError(file_.path, "",
                             "holds no ring-width series: expected Tucson .rwl data lines");
        return std::move(file_);
    }

private:
    /// A data line of the current series (opened by it if none is open).
    void readSeriesLine(const DataLine& d) {
        if (!open_) openSeries(d);
        checkLineStart(d);
        appendValues(d);
        if (raw_.back() == kMarkerThousandths) {
            closeSeries(lineNo_);
            return;
        }
        // A line that stops before its decade's end closes the series (999 is then the marker).
        if ((nextYear_ % 10 + 10) % 10 != 0) closeSeries(lineNo_);
    }

    /// The current series is bad: it keeps no widths, and its later lines are skipped.
    void markBad(const SeriesProblem& p) {
        current_.problem = p.message;
        current_.problemLine = p.line;
        current_.widthsMm.clear();
        raw_.clear();
    }

    /// Lines that are not data are the header while no data line came yet (at most 8 of them).
    void readHeaderLine(const std::string& line) {
        if (lastDataLine_ == 0 && file_.header.size() < 8) {
            file_.header.push_back(trim(line));
            return;
        }
        throw InputError(file_.path, lineAt(lineNo_),
                         "expected a data line: a series ID (columns 1-8), a year (columns "
                         "9-12) and up to ten integer widths in 6-character fields");
    }

    void openSeries(const DataLine& d) {
        current_.id = d.id;
        current_.firstYear = static_cast<int>(d.year);
        current_.firstLine = lineNo_;
        nextYear_ = d.year;
        open_ = true;
        if (ended_.count(d.id))
            throw SeriesProblem{lineNo_, fmt::format("series '{}' starts again after its end "
                                                     "marker: expected each series once",
                                                     d.id)};
    }

    /// A line continues its series where the previous one stopped, at a decade year.
    void checkLineStart(const DataLine& d) const {
        if (d.year != nextYear_)
            throw SeriesProblem{lineNo_, fmt::format("series '{}' jumps from year {} to {}: "
                                                     "expected the line to start at year {}",
                                                     d.id, nextYear_ - 1, d.year, nextYear_)};
        if (d.year != current_.firstYear && d.year % 10 != 0)
            throw SeriesProblem{lineNo_, fmt::format("series '{}' continues at year {}: expected "
                                                     "a line to start at a decade year",
                                                     d.id, d.year)};
    }

    void appendValues(const DataLine& d) {
        for (size_t i = 0; i < d.values.size(); ++i) {
            long v = d.values[i];
            bool last = i + 1 == d.values.size();
            if (v == kMarkerThousandths && !last)
                throw SeriesProblem{
                    lineNo_, fmt::format("series '{}': values after the end marker -9999", d.id)};
            if (v < 0 && v != kMarkerThousandths)
                throw SeriesProblem{lineNo_,
                                    fmt::format("series '{}', year {}: width {} is "
                                                "negative: expected a width >= 0 or an "
                                                "end marker",
                                                d.id, nextYear_ + static_cast<long>(i), v)};
            raw_.push_back(v);
        }
        nextYear_ += static_cast<long>(d.values.size());
    }

    /// Ends the current series (`n`: the line it ended on, for the messages); a good one gets
    /// its widths, a bad one stays listed with its problem.
    void closeSeries(int n) {
        if (!current_.bad()) {
            try {
                takeWidths(n);
            } catch (const SeriesProblem& p) {
                markBad(p);
            }
        }
        ended_.insert(current_.id);
        file_.series.push_back(std::move(current_));
        current_ = RingSeries{};
        raw_.clear();
        open_ = false;
    }

    /// The series' widths in mm: its last value is its end marker, which sets the unit.
    void takeWidths(int n) {
        long marker = raw_.empty() ? 0 : raw_.back();
        if (marker == kMarkerThousandths)
            current_.unitMm = 0.001;
        else if (marker == kMarkerHundredths)
            current_.unitMm = 0.01;
        else
            throw SeriesProblem{n, fmt::format("series '{}' ends without its end marker: "
                                               "expected 999 (0.01 mm) or -9999 (0.001 mm) after "
                                               "year {}",
                                               current_.id, nextYear_ - 1)};
        raw_.pop_back();
        if (raw_.empty())
            throw SeriesProblem{
                n, fmt::format("series '{}' has no widths before its end marker", current_.id)};
        for (long v : raw_) current_.widthsMm.push_back(static_cast<double>(v) * current_.unitMm);
    }

    RingSeriesFile file_;
    std::set<std::string> ended_;  ///< IDs of the series already closed
    RingSeries current_;
    std::vector<long> raw_;  ///< the current series' values as written, marker included
    bool open_ = false;
    long nextYear_ = 0;  ///< the year the current series' next value is for
    int lineNo_ = 0, lastDataLine_ = 0;
};

}  // namespace

const RingSeries& RingSeriesFile::find(const std::string& id) const {
    const RingSeries* found = nullptr;
    for (const auto& s : series) {
        if (s.id != id) continue;
        // Refused at its line, as if the file held only this series.
        if (s.bad()) throw InputError(path, lineAt(s.problemLine), s.problem);
        if (!found) found = &s;
    }
    if (found) return *found;
    std::string ids;
    for (size_t i = 0; i < series.size() && i < 12; ++i) ids += (i ? ", " : "") + series[i].id;
    if (series.size() > 12) ids += fmt::format(", … ({} in all; --list shows them)", series.size());
    throw InputError(path, "", fmt::format("no series '{}': expected one of {}", id, ids));
}

RingSeriesFile readTucsonRwl(const std::string& path) {
    return parseTucsonRwl(readInputFile(path, kMaxFileBytes, "a Tucson .rwl text file"), path);
}

RingSeriesFile parseTucsonRwl(const std::string& text, const std::string& path) {
    TucsonReader reader(path);
    std::istringstream lines(text);
    std::string line;
    while (std::getline(lines, line)) reader.readLine(line);
    return reader.finish();
}

std::vector<double> latewoodShares(const RingSeries& e, const RingSeriesFile& latewood) {
    const RingSeries& l = latewood.find(e.id);
    if (l.lastYear() < e.firstYear || l.firstYear > e.lastYear())
        throw InputError(latewood.path, fmt::format("line {}", l.firstLine),
                         fmt::format("series '{}' covers {}-{}: expected years that overlap "
                                     "the earlywood series' {}-{}",
                                     l.id, l.firstYear, l.lastYear(), e.firstYear, e.lastYear()));
    // Measured cores do not always have both parts for every year (nm580l is shorter than
    // nm580e for some cores): years without a latewood value, or with e + l = 0, get the
    // series' mean share.
    std::vector<double> shares(e.widthsMm.size(), -1);
    double sum = 0;
    int count = 0;
    for (size_t i = 0; i < shares.size(); ++i) {
        int year = e.firstYear + static_cast<int>(i);
        if (year < l.firstYear || year > l.lastYear()) continue;
        double late = l.widthsMm[static_cast<size_t>(year - l.firstYear)];
        double total = e.widthsMm[i] + late;
        if (total > 0) {
            shares[i] = late / total;
            sum += shares[i], ++count;
        }
    }
    double mean = count ? sum / count : 0.3;
    for (double& s : shares)
        if (s < 0) s = mean;
    return shares;
}

RingSeries totalFromEarlyLate(const RingSeries& e, const RingSeriesFile& latewood) {
    const std::vector<double> shares = latewoodShares(e, latewood);
    RingSeries total = e;
    for (size_t i = 0; i < total.widthsMm.size(); ++i)
        total.widthsMm[i] = e.widthsMm[i] / (1 - std::min(shares[i], 0.99));
    return total;
}

RingStatistics ringStatistics(const std::vector<double>& w) {
    RingStatistics r;
    size_t n = w.size();
    if (n < 2) return r;
    for (double x : w) r.mean += x;
    r.mean /= double(n);
    double var = 0, cov = 0, sens = 0;
    int pairs = 0;
    for (size_t i = 0; i < n; ++i) {
        var += (w[i] - r.mean) * (w[i] - r.mean);
        if (i + 1 < n) {
            cov += (w[i] - r.mean) * (w[i + 1] - r.mean);
            double s = w[i] + w[i + 1];
            if (s > 0) sens += std::abs(2 * (w[i + 1] - w[i]) / s), ++pairs;
        }
    }
    r.cv = r.mean > 0 ? std::sqrt(var / double(n - 1)) / r.mean : 0;
    r.autocorrelation = var > 0 ? cov / var : 0;
    r.meanSensitivity = pairs ? sens / pairs : 0;
    return r;
}

std::vector<double> ringWidthsMetres(const RingSeries& s, double meanWidthMm,
                                     const std::string& file) {
    double mean = 0;
    for (double w : s.widthsMm) mean += w;
    mean /= double(s.widthsMm.size());
    if (!(mean > 0))
        throw InputError(file, "", fmt::format("series '{}' has only zero-width rings", s.id));
    double scale = meanWidthMm > 0 ? meanWidthMm / mean : 1.0;
    std::vector<double> metres;
    metres.reserve(s.widthsMm.size());
    for (double w : s.widthsMm) metres.push_back(w * scale * 1e-3);
    return metres;
}

}  // namespace nenrin
