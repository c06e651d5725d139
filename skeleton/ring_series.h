#pragma once
/// Measured yearly ring widths: the Tucson "decadal" .rwl format of dendrochronology (ITRDB),
/// read strictly (docs/ring-series.md). A file holds many series, one per tree core; each
/// series becomes a skeleton's `ring_widths` (Skeleton::ringWidths) on request.
///
/// Format: optional header lines (site ID, then 1, 2, 3 in columns 7-9, free text) before the
/// first data line. A data line is the series ID (columns 1-8), the year of its first value
/// (columns 9-12, negative for BCE) and up to ten widths in 6-character fields for consecutive
/// years. A series ends with the marker 999 (its widths are in 0.01 mm) or -9999 (0.001 mm).
/// 0 is a real value: a ring locally absent at that radius.

#include <string>
#include <vector>

namespace nenrin {

struct RingSeries {
    std::string id;
    int firstYear = 0;
    double unitMm = 0.01;          ///< 0.01 (marker 999) or 0.001 (marker -9999)
    std::vector<double> widthsMm;  ///< one per year from firstYear, >= 0
    int firstLine = 0;             ///< 1-based line of the series' first data line
    /// What is wrong with this series (a negative width, a year gap, no end marker...), empty
    /// when nothing is; `problemLine` is where. A bad series has no widths: it is listed, never
    /// used, and the file's other series are unaffected.
    std::string problem;
    int problemLine = 0;
    bool bad() const { return !problem.empty(); }
    int lastYear() const { return firstYear + static_cast<int>(widthsMm.size()) - 1; }
};

struct RingSeriesFile {
    std::string path;
    std::vector<std::string> header;  ///< the header lines as written
    std::vector<RingSeries> series;   ///< in file order
    /// The good series with this ID; throws InputError listing the IDs when there is none, or
    /// naming the line and the problem when that series is bad.
    const RingSeries& find(const std::string& id) const;
};

/// Throws InputError naming the file, the line and what was expected when the file as a whole
/// cannot be read (not text, a line that is no data line, no series); a problem inside one
/// series marks that series (RingSeries::problem) and reading goes on.
RingSeriesFile readTucsonRwl(const std::string& path);
RingSeriesFile parseTucsonRwl(const std::string& text, const std::string& path);

/// Per-year latewood share l / (e + l), one per year of the earlywood series, from an
/// earlywood and a latewood file of the same cores; years without a latewood value or with
/// e + l = 0 get the series' mean share. Throws InputError when the latewood file lacks the
/// series or shares no year with it.
std::vector<double> latewoodShares(const RingSeries& earlywood, const RingSeriesFile& latewood);

/// The total ring widths of a core from its earlywood series and the latewood file: e + l per
/// year, e / (1 - the year's share) where the latewood value is missing (latewoodShares).
RingSeries totalFromEarlyLate(const RingSeries& earlywood, const RingSeriesFile& latewood);

/// Summary statistics of a width series, as dendrochronologists state them.
struct RingStatistics {
    double mean = 0, cv = 0;     ///< mean width and coefficient of variation (sd / mean)
    double autocorrelation = 0;  ///< lag-1 autocorrelation
    double meanSensitivity =
        0;  ///< mean of |2 (w_t+1 - w_t) / (w_t+1 + w_t)|, pairs with a sum > 0
};
RingStatistics ringStatistics(const std::vector<double>& widths);

/// A series as `ring_widths` in metres: scaled to `meanWidthMm` when it is > 0. Zero rings stay
/// zero (a merged ring); throws InputError if every ring is zero.
std::vector<double> ringWidthsMetres(const RingSeries& series, double meanWidthMm,
                                     const std::string& file);

}  // namespace nenrin
