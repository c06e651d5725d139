#include "skeleton/sources/akagi/akagi_observations.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "util/input_error.h"
#include "util/input_file.h"

namespace nenrin {

namespace {

std::string trim(const std::string& s) {
    size_t b = s.find_first_not_of(" \t\r"), e = s.find_last_not_of(" \t\r");
    return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

std::vector<std::string> splitFields(const std::string& line) {
    std::vector<std::string> fields;
    std::string field;
    std::istringstream in(line);
    while (std::getline(in, field, ',')) fields.push_back(trim(field));
    if (!line.empty() && line.back() == ',') fields.push_back("");
    return fields;
}

std::string lineAt(int line) { return "line " + std::to_string(line); }

/// The header's columns: per column -1 for `tree`, else the parameter's index. Every parameter
/// and `tree` must appear exactly once.
std::vector<int> readHeader(const std::vector<std::string>& fields, const std::string& source,
                            int lineNo) {
    std::vector<int> columnParam;
    std::vector<bool> seen(kAkagiParamCount, false);
    bool seenTree = false;
    for (const std::string& name : fields) {
        if (name == "tree") {
            if (seenTree) throw InputError(source, lineAt(lineNo), "column 'tree' twice");
            seenTree = true;
            columnParam.push_back(-1);
            continue;
        }
        int i = akagiParamIndex(name);
        if (i < 0)
            throw InputError(source, lineAt(lineNo),
                             "unknown column '" + name +
                                 "' (expected 'tree' and the 13 parameter names, "
                                 "Height ... GrowthGain)");
        if (seen[i]) throw InputError(source, lineAt(lineNo), "column '" + name + "' twice");
        seen[i] = true;
        columnParam.push_back(i);
    }
    if (!seenTree) throw InputError(source, lineAt(lineNo), "the header lacks column 'tree'");
    for (int i = 0; i < kAkagiParamCount; ++i)
        if (!seen[i])
            throw InputError(source, lineAt(lineNo),
                             std::string("the header lacks column '") + akagiParamNames()[i] + "'");
    return columnParam;
}

/// The index of tree `id` in the table's trees, adding it when it is new.
int treeIndexOf(ObservationTable& table, const std::string& id, int lineNo) {
    if (id.empty()) throw InputError(table.source, lineAt(lineNo), "empty tree id");
    int treeIndex = -1;
    for (size_t t = 0; t < table.treeIds.size(); ++t)
        if (table.treeIds[t] == id) treeIndex = static_cast<int>(t);
    if (treeIndex < 0) {
        treeIndex = static_cast<int>(table.treeIds.size());
        table.treeIds.push_back(id);
    }
    return treeIndex;
}

/// Parameter `i`'s value in field `f`: a number in the parameter's range, and > 0 where the
/// model draws the parameter from a Gamma distribution.
double readParamValue(int i, const std::string& f, const std::string& source, int lineNo) {
    const char* name = akagiParamNames()[i];
    char* end = nullptr;
    errno = 0;
    double v = std::strtod(f.c_str(), &end);
    if (f.empty() || *end != '\0' || errno == ERANGE)
        throw InputError(
            source, lineAt(lineNo),
            std::string("column '") + name + "': expected a number, found '" + f + "'");
    std::string problem = akagiParamProblem(i, v);
    // The model's Gamma likelihood needs MainGrowth > 0: a dichotomous fork is written with a
    // small share (its main child then never grows past a leaf).
    if (problem.empty() && i == 5 && v <= 0)
        problem =
            "expected a number > 0 (Gamma-distributed in the model; write a small "
            "share such as 0.001 for a dichotomous fork), found 0";
    if (problem.empty() && i == 12 && v <= 0)
        problem = "expected a number > 0 (Gamma-distributed in the model), found " + f;
    if (problem.empty() && i == 2 && v <= 0)
        problem = "expected a number > 0 (Gamma-distributed in the model), found " + f;
    if (!problem.empty())
        throw InputError(source, lineAt(lineNo), std::string("column '") + name + "': " + problem);
    return v;
}

/// One observation row, its fields checked in column order.
void readRow(ObservationTable& table, const std::vector<std::string>& fields,
             const std::vector<int>& columnParam, int lineNo) {
    if (fields.size() != columnParam.size())
        throw InputError(table.source, lineAt(lineNo),
                         "expected " + std::to_string(columnParam.size()) + " fields, found " +
                             std::to_string(fields.size()));
    AkagiParams row;
    int treeIndex = -1;
    for (size_t c = 0; c < fields.size(); ++c) {
        if (columnParam[c] < 0)
            treeIndex = treeIndexOf(table, fields[c], lineNo);
        else
            row[columnParam[c]] = readParamValue(columnParam[c], fields[c], table.source, lineNo);
    }
    table.rows.push_back(row);
    table.rowTree.push_back(treeIndex);
    table.rowLine.push_back(lineNo);
}

/// At least 2 trees and 4 rows (docs/tree-akagi.md, "Observation tables").
void checkTableSize(const ObservationTable& table) {
    if (table.treeIds.size() < 2)
        throw InputError(table.source, "",
                         "expected observations of at least 2 trees, found " +
                             std::to_string(table.treeIds.size()));
    if (table.rows.size() < 4)
        throw InputError(
            table.source, "",
            "expected at least 4 observation rows, found " + std::to_string(table.rows.size()));
}

}  // namespace

ObservationTable parseAkagiObservations(const std::string& text, const std::string& source) {
    ObservationTable table;
    table.source = source;
    std::istringstream in(text);
    std::string raw;
    int lineNo = 0;
    std::vector<int> columnParam;  // per column: -1 = tree, else the parameter index
    bool haveHeader = false;
    while (std::getline(in, raw)) {
        ++lineNo;
        std::string line = trim(raw);
        if (line.empty() || line[0] == '#') continue;
        std::vector<std::string> fields = splitFields(line);
        if (!haveHeader) {
            columnParam = readHeader(fields, source, lineNo);
            haveHeader = true;
        } else {
            readRow(table, fields, columnParam, lineNo);
        }
    }
    if (!haveHeader) throw InputError(source, "", "no header line (and no observations)");
    checkTableSize(table);
    return table;
}

ObservationTable loadAkagiObservations(const std::string& path) {
    return parseAkagiObservations(readInputFile(path, size_t(64) << 20, "a CSV observation table"),
                                  path);
}

}  // namespace nenrin
