#pragma once
// A comma- or blank-separated text table, as point cloud files are written: blank
// lines are skipped, the first line that holds something (a leading '#' dropped) names
// the columns, and later lines starting with '#' are comments. Both point cloud readers
// read theirs with it (2D: point_cloud_file.cpp, 3D: point_cloud3d.cpp).
#include <istream>
#include <string>
#include <vector>

namespace bapd {

// The next line of `in` that holds something, its leading blanks removed; header: the
// line expected is the header (a leading '#' is dropped), otherwise comment lines are
// skipped. *number counts the file's lines read. false at the end of the input.
bool next_table_line(std::istream &in, bool header, long *number, std::string *trimmed);

// The tokens of a line, split at commas and blanks; lower: in lower case.
std::vector<std::string> table_tokens(const std::string &line, bool lower);

// A point table's header, line `line` of `file`: (*at)[k] the column named columns[k] (in
// any case; "block_id|block" lists a name and its alias), -1 where none is; the first
// `required` columns must be there. Returns "" or the message naming the file, the line
// and the fix: the line holds numbers, names a column twice or lacks a required one
// (quoted: the header line as the message shows it, "" for none).
std::string table_header(const std::string &file, long line, const std::vector<std::string> &header, const std::string &quoted,
                         const std::vector<std::string> &columns, std::size_t required, std::vector<int> *at);

// Whether the whole token is a number (strtod), and its value.
bool table_number(const std::string &token, double *value);

} // namespace bapd
