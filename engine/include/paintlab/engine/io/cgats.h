#pragma once
// CGATS.17 / IT8.7 text (colord's CIE tables, instruments' spectra exports)
// read through liblcms2's cmsIT8 parser, which accepts the keywords and
// data-format names of any instrument. The one CGATS reader of PaintLab: the
// engine's CIE tables (colour/cie_tables.h) and the database's spectra
// imports interpret the table it returns. No lcms2 type appears here.

#include <cstddef>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace paintlab::io {

struct CgatsTable {
    // Header keywords and their values as text (lcms2 writes numbers back
    // with 10 significant digits), NUMBER_OF_FIELDS and NUMBER_OF_SETS included.
    std::map<std::string, std::string, std::less<>> properties;
    std::vector<std::string> columns;            // the DATA_FORMAT names, in file order
    std::vector<std::vector<std::string>> rows;  // NUMBER_OF_SETS rows of cells; "" where none was given

    // The keyword's value, "" when absent.
    std::string property(std::string_view key) const;
    // How many cells hold a value.
    std::size_t valueCount() const;
};

// Parses text holding exactly one table. Throws InputError(source, "", ...)
// with lcms2's messages (which give the line) for text it cannot read, and
// for a file of several tables.
CgatsTable parseCgats(std::string_view text, const std::string& source);

}  // namespace paintlab::io
