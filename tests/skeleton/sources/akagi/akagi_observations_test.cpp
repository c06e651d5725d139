// The observation-table reader of the Akagi model: format, and file:line errors.
#include "skeleton/sources/akagi/akagi_observations.h"

#include <gtest/gtest.h>

#include "util/input_error.h"

namespace nenrin {
namespace {

const std::string kHeader =
    "tree,Height,Radius,LeafNum,LeafSize,BranchNum,MainGrowth,MainAngle,MainRotation,"
    "SubGrowth,SubAngle,BranchPoint,Horizontal,GrowthGain\n";
const std::string kRow = "10,0.2,5,0.08,3,0.6,5,137,0.2,45,0.3,0.2,0.5\n";

std::string errorOf(const std::string& text) {
    try {
        parseAkagiObservations(text, "t.csv");
    } catch (const InputError& e) {
        return e.what();
    }
    return "no error";
}

TEST(AkagiObservations, ReadsRowsTreesAndComments) {
    std::string text = "# comment\n\n" + kHeader + "a," + kRow + "  # another\na," + kRow + "b," +
                       kRow + "b," + kRow;
    ObservationTable t = parseAkagiObservations(text, "t.csv");
    ASSERT_EQ(t.rows.size(), 4u);
    EXPECT_EQ(t.treeIds, (std::vector<std::string>{"a", "b"}));
    EXPECT_EQ(t.rowTree, (std::vector<int>{0, 0, 1, 1}));
    EXPECT_EQ(t.rowLine[2], 7);
    EXPECT_DOUBLE_EQ(t.rows[0].mainRotation, 137);
    EXPECT_DOUBLE_EQ(t.rows[3].growthGain, 0.5);
}

TEST(AkagiObservations, ColumnsMayComeInAnyOrder) {
    std::string text =
        "GrowthGain,tree,Height,Radius,LeafNum,LeafSize,BranchNum,MainGrowth,MainAngle,"
        "MainRotation,SubGrowth,SubAngle,BranchPoint,Horizontal\n";
    for (const char* tree : {"a", "a", "b", "b"})
        text += std::string("0.7,") + tree + ",10,0.2,5,0.08,3,0.6,5,137,0.2,45,0.3,0.2\n";
    ObservationTable t = parseAkagiObservations(text, "t.csv");
    EXPECT_DOUBLE_EQ(t.rows[0].growthGain, 0.7);
    EXPECT_DOUBLE_EQ(t.rows[0].height, 10);
}

TEST(AkagiObservations, BadTablesNameFileAndLine) {
    std::string rows = "a," + kRow + "a," + kRow + "b," + kRow;
    EXPECT_EQ(
        errorOf("# c\n" + kHeader + rows + "b,10,0.2,5,0.08,3,0.6,5,137,0.2,4x,0.3,0.2,0.5\n"),
        "t.csv: line 6: column 'SubAngle': expected a number, found '4x'");
    EXPECT_EQ(errorOf(kHeader + rows + "b,10,0.2\n"), "t.csv: line 5: expected 14 fields, found 3");
    EXPECT_EQ(errorOf(kHeader + rows + "b,10,0.2,5,0.08,3,1.5,5,137,0.2,45,0.3,0.2,0.5\n"),
              "t.csv: line 5: column 'MainGrowth': expected a number in [0, 1) (share), found 1.5");
    EXPECT_NE(errorOf(kHeader + rows + "b,10,0.2,5,0.08,3,0,5,137,0.2,45,0.3,0.2,0.5\n")
                  .find("line 5: column 'MainGrowth': expected a number > 0"),
              std::string::npos);
    EXPECT_EQ(errorOf("tree,Height,Heigth\n"),
              "t.csv: line 1: unknown column 'Heigth' (expected 'tree' and the 13 parameter "
              "names, Height ... GrowthGain)");
    EXPECT_EQ(errorOf("tree,Height\n"), "t.csv: line 1: the header lacks column 'Radius'");
    EXPECT_EQ(errorOf(kHeader + "a," + kRow + "a," + kRow + "a," + kRow + "a," + kRow),
              "t.csv: expected observations of at least 2 trees, found 1");
    EXPECT_EQ(errorOf("# only a comment\n"), "t.csv: no header line (and no observations)");
}

TEST(AkagiObservations, MissingFileIsAnInputError) {
    try {
        loadAkagiObservations("/nonexistent/akagi.csv");
        FAIL();
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), "/nonexistent/akagi.csv");
    }
}

}  // namespace
}  // namespace nenrin
