#include "skeleton/ring_series.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "util/input_error.h"

namespace nenrin {
namespace {

const std::string kRings = std::string(NENRIN_SOURCE_DIR) + "/data/rings/";

TEST(RingSeries, ReadsThousandthsWithHeader) {
    RingSeriesFile f = readTucsonRwl(kRings + "nm580.rwl");
    EXPECT_EQ(f.header.size(), 3u);
    EXPECT_EQ(f.series.size(), 119u);
    const RingSeries& s = f.find("BCS05B");
    EXPECT_EQ(s.firstYear, 1370);
    EXPECT_EQ(s.lastYear(), 1990);
    EXPECT_DOUBLE_EQ(s.unitMm, 0.001);
    EXPECT_NEAR(s.widthsMm.front(), 1.373, 1e-12);  // "BCS05B  1370  1373"
    EXPECT_NEAR(s.widthsMm.back(), 0.467, 1e-12);   // "BCS05B  1990   467 -9999"
}

TEST(RingSeries, ReadsHundredthsZeroRingsAndMidDecadeStarts) {
    RingSeriesFile f = readTucsonRwl(kRings + "co021.rwl");  // no header, CR LF lines
    EXPECT_TRUE(f.header.empty());
    EXPECT_EQ(f.series.size(), 35u);
    const RingSeries& s = f.find("641114");
    EXPECT_DOUBLE_EQ(s.unitMm, 0.01);
    EXPECT_EQ(s.firstYear, 1270);
    EXPECT_EQ(s.lastYear(), 1963);
    EXPECT_NEAR(s.widthsMm[0], 1.48, 1e-12);
    EXPECT_EQ(f.find("641132").firstYear, 1256);  // starts mid-decade
    size_t zeros = 0;
    for (const auto& series : f.series)
        for (double w : series.widthsMm) {
            EXPECT_GE(w, 0);
            zeros += w == 0;
        }
    EXPECT_GT(zeros, 0u);  // locally absent rings are kept as 0
}

TEST(RingSeries, EarlywoodPlusLatewoodIsTheTotalWithinRounding) {
    RingSeriesFile total = readTucsonRwl(kRings + "nm580.rwl");
    RingSeriesFile early = readTucsonRwl(kRings + "nm580e.rwl");
    RingSeriesFile late = readTucsonRwl(kRings + "nm580l.rwl");
    size_t years = 0, within = 0;
    auto has = [](const RingSeriesFile& f, const std::string& id) {
        return std::any_of(f.series.begin(), f.series.end(),
                           [&](const RingSeries& s) { return s.id == id; });
    };
    for (const auto& l : late.series) {
        if (!has(early, l.id) || !has(total, l.id)) continue;  // a few cores lack a part
        const RingSeries& e = early.find(l.id);
        const RingSeries& t = total.find(l.id);
        for (size_t i = 0; i < l.widthsMm.size(); ++i) {
            int year = l.firstYear + int(i);
            if (year < t.firstYear || year > t.lastYear() || year < e.firstYear ||
                year > e.lastYear())
                continue;
            ++years;
            double sum = e.widthsMm[size_t(year - e.firstYear)] + l.widthsMm[i];
            within += std::abs(sum - t.widthsMm[size_t(year - t.firstYear)]) <= 0.002 + 1e-9;
        }
        std::vector<double> shares = latewoodShares(e, late);
        ASSERT_EQ(shares.size(), e.widthsMm.size());
        for (double s : shares) EXPECT_TRUE(s >= 0 && s <= 1) << l.id;
    }
    EXPECT_GT(years, 30000u);
    EXPECT_GE(double(within) / double(years), 0.999);  // the README: 32 221 of 32 233
}

TEST(RingSeries, MeasuredStatisticsAreThoseOfRealTrees) {
    // The facts the stochastic ring model is built to: real cores are irregular and
    // persistent. Medians over the co021 and nm580 cores.
    std::vector<double> cv, ar, ms;
    for (const char* name : {"co021.rwl", "nm580.rwl"})
        for (const auto& s : readTucsonRwl(kRings + name).series) {
            RingStatistics st = ringStatistics(s.widthsMm);
            cv.push_back(st.cv), ar.push_back(st.autocorrelation), ms.push_back(st.meanSensitivity);
        }
    auto median = [](std::vector<double> v) {
        std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
        return v[v.size() / 2];
    };
    EXPECT_GT(median(cv), 0.4);
    EXPECT_LT(median(cv), 0.9);
    EXPECT_GT(median(ar), 0.3);
    EXPECT_LT(median(ar), 0.8);
    EXPECT_GT(median(ms), 0.2);
    EXPECT_LT(median(ms), 0.6);
}

TEST(RingSeries, StatisticsOfAKnownSeries) {
    RingStatistics s = ringStatistics({1, 3, 1, 3});
    EXPECT_DOUBLE_EQ(s.mean, 2);
    EXPECT_NEAR(s.cv, std::sqrt(4.0 / 3.0) / 2, 1e-12);
    EXPECT_NEAR(s.autocorrelation, -3.0 / 4.0, 1e-12);
    EXPECT_NEAR(s.meanSensitivity, 1.0, 1e-12);
}

TEST(RingSeries, WidthsInMetresScaledToAMean) {
    RingSeries s;
    s.id = "A";
    s.widthsMm = {1, 0, 3};
    std::vector<double> m = ringWidthsMetres(s, 0, "f");
    EXPECT_DOUBLE_EQ(m[0], 0.001);
    EXPECT_DOUBLE_EQ(m[1], 0);
    EXPECT_DOUBLE_EQ(m[2], 0.003);
    std::vector<double> scaled = ringWidthsMetres(s, 4, "f");
    EXPECT_NEAR(scaled[2], 0.009, 1e-15);  // mean 4/3 mm -> 4 mm: x3
    s.widthsMm = {0, 0};
    EXPECT_THROW(ringWidthsMetres(s, 0, "f"), InputError);
}

/// The error of reading the file and then using its series AB01 (a series' own problem
/// appears when it is used; the file's, when it is read).
std::string errorOf(const std::string& text) {
    try {
        parseTucsonRwl(text, "bad.rwl").find("AB01");
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

TEST(RingSeries, BadLinesNameTheLineAndWhatWasExpected) {
    const std::string ok1 =
        "AB01    1990   100   200   300   400   500   600   700   800   900  1000\n";
    EXPECT_EQ(errorOf(ok1 + "AB01    2000   100   999\n"), "no error");
    auto expectError = [](const std::string& text, const std::string& where,
                          const std::string& what) {
        std::string e = errorOf(text);
        EXPECT_NE(e.find("bad.rwl"), std::string::npos) << e;
        EXPECT_NE(e.find(where), std::string::npos) << e;
        EXPECT_NE(e.find(what), std::string::npos) << e;
    };
    expectError(ok1 + "AB01    2000   100   -50   999\n", "line 2", "negative");
    expectError(ok1 + "AB01    2010   100   999\n", "line 2", "jumps from year 1999 to 2010");
    expectError(ok1 + "AB01    2000   100   999\nAB01    2010    20   999\n", "line 3",
                "starts again after its end marker");
    expectError(ok1 + "AB01    2000   100   120\nCD02    2000   100   999\n", "line 2",
                "without its end marker");
    expectError(ok1 + "AB01    2000   100 -9999    20\n", "line 2", "after the end marker");
    expectError(ok1 + "AB01    2000   1x0   999\n", "line 2", "expected a data line");
    expectError("just some text\n", "bad.rwl", "no ring-width series");
    expectError(std::string("AB01    1990   100\0  999\n", 25), "line 1", "NUL");
}

TEST(RingSeries, ARealFileWithANegativeWidthStopsOnlyThatSeries) {
    // wa082.rwl holds -999 for year 1900 of series 712011: that series is marked with its
    // line and refused when used; the file's other 22 series are read as they are.
    RingSeriesFile f = readTucsonRwl(kRings + "wa082.rwl");
    ASSERT_EQ(f.series.size(), 23u);
    EXPECT_TRUE(f.series[0].bad());
    EXPECT_EQ(f.series[0].id, "712011");
    EXPECT_EQ(f.series[0].problemLine, 13);
    EXPECT_TRUE(f.series[0].widthsMm.empty());
    for (size_t i = 1; i < f.series.size(); ++i) EXPECT_FALSE(f.series[i].bad()) << i;
    EXPECT_EQ(f.find("712012").widthsMm.size(), 214u);
    try {
        f.find("712011");
        FAIL() << "a bad series was handed out";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("line 13"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("width -999 is negative"), std::string::npos)
            << e.what();
    }
}

TEST(RingSeries, OneBadValueInAThousandthsFileSparesTheOtherSeries) {
    // The shape of ITRDB's th001.rwl: 0.001 mm units, one value -2599 in series PATUNG (1928).
    const std::string text =
        "PATUNG  1920   812   903   755   680   700   640   590   602   611   580\n"
        "PATUNG  1930   575   560 -2599   540   530   520   510   500   490   480\n"
        "PATUNG  1940   470   460 -9999\n"
        "PATOLD  1921   900   880   860   840   820   800   780   760   740\n"
        "PATOLD  1930   720   700 -9999\n";
    RingSeriesFile f = parseTucsonRwl(text, "th.rwl");
    ASSERT_EQ(f.series.size(), 2u);
    EXPECT_TRUE(f.series[0].bad());
    EXPECT_EQ(f.series[0].problemLine, 2);
    EXPECT_NE(f.series[0].problem.find("year 1932: width -2599 is negative"), std::string::npos)
        << f.series[0].problem;
    const RingSeries& good = f.find("PATOLD");
    EXPECT_EQ(good.firstYear, 1921);
    EXPECT_EQ(good.widthsMm.size(), 11u);
    EXPECT_DOUBLE_EQ(good.unitMm, 0.001);
    EXPECT_THROW(f.find("PATUNG"), InputError);
}

TEST(RingSeries, DeviceFilesAndMissingFilesAreRefused) {
    EXPECT_THROW(readTucsonRwl("/dev/zero"), InputError);  // endless: stopped by the size cap
    EXPECT_THROW(readTucsonRwl("/no/such/file.rwl"), InputError);
}

}  // namespace
}  // namespace nenrin
