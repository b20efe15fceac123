// The shared file pieces (engine/include/paintlab/engine/io/): numbers as
// printf would write them in the C locale, whatever the locale; the atomic
// writer; CSV quoting and reading back.

#include "temp_dir.h"

#include "paintlab/engine/error.h"
#include "paintlab/engine/io/atomic_file.h"
#include "paintlab/engine/io/csv.h"
#include "paintlab/engine/io/number_format.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace paintlab {
namespace {

namespace fs = std::filesystem;

std::string printfG(int precision, double value) {
    char buffer[512];
    std::snprintf(buffer, sizeof buffer, "%.*g", precision, value);
    return buffer;
}

std::string printfF(int decimals, double value) {
    char buffer[512];
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
    return buffer;
}

TEST(NumberFormat, MatchesPrintfInTheCLocale) {
    for (const double v : {0.0, -0.0, 1.0, 0.1, 1.0 / 3.0, 123456.0, 1234567.0, 1e-5, 2.5e-7, -42.125, 1e300,
                           std::numeric_limits<double>::infinity()}) {
        EXPECT_EQ(io::formatNumber(v), printfG(6, v)) << v;
        EXPECT_EQ(io::formatNumber(v, io::NumberFormat::Brief), printfG(4, v)) << v;
        EXPECT_EQ(io::formatNumber(v, io::NumberFormat::Digits17), printfG(17, v)) << v;
        EXPECT_EQ(io::formatFixed(v, 3), printfF(3, v)) << v;
        EXPECT_EQ(std::stod(io::formatNumber(v, io::NumberFormat::Shortest)), v) << v;
    }
    EXPECT_EQ(io::formatNumber(0.1, io::NumberFormat::Shortest), "0.1");
}

// The plan's and the validity rule's reasons: printf's conversions, any length.
TEST(NumberFormat, FormatTextIsPrintfWithoutALengthLimit) {
    EXPECT_EQ(io::formatText("%.3g um, %+.1f %%, %.0f deg, %s %d", 0.0123456, 12.34, 44.5, "light", 7),
              "0.0123 um, +12.3 %, 44 deg, light 7");
    const std::string long_name(300, 'x');
    const std::string text = io::formatText("light '%s' %.2g", long_name.c_str(), 0.5);
    EXPECT_EQ(text, "light '" + long_name + "' 0.5");  // the plan's old 256-byte buffer cut this
    EXPECT_EQ(io::formatText("%s", ""), "");
}

class AtomicFile : public ::testing::Test {
protected:
    void SetUp() override {
        m_dir = fs::temp_directory_path() / ("paintlab_io_" + std::to_string(::getpid()));
        fs::create_directories(m_dir);
    }
    void TearDown() override {
        std::error_code ignored;
        fs::remove_all(m_dir, ignored);
    }
    fs::path m_dir;
};

TEST_F(AtomicFile, ReplacesTheFileAndLeavesNoTemporary) {
    const fs::path file = m_dir / "out.txt";
    io::writeFileAtomically(file, "old");
    io::writeFileAtomically(file, std::string("new\0bytes", 9));
    std::ifstream in(file, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    EXPECT_EQ(text.str(), std::string("new\0bytes", 9));
    EXPECT_EQ(test::entriesOf(m_dir), std::vector<std::string>{"out.txt"});  // no temporary left
}

TEST_F(AtomicFile, AMissingFolderIsAnInputErrorNamingTheFile) {
    const fs::path file = m_dir / "no such folder" / "out.txt";
    try {
        io::writeFileAtomically(file, "x");
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(e.source(), file.string());
        EXPECT_NE(std::string(e.what()).find("cannot open for writing"), std::string::npos) << e.what();
    }
}

TEST(Csv, QuotedFieldsReadBack) {
    const std::string text = io::csvLine({"name", "note", "value"}) +
                             io::csvLine({"a, b", "say \"hi\"\nbye", io::csvNumber(0.1)}) +
                             io::csvJoin({"plain", "", io::csvNumber(std::optional<double>())});
    const io::CsvTable table = io::CsvTable::parse(text, "t.csv");
    ASSERT_EQ(table.records().size(), 2U);
    const io::CsvRecord& first = table.records()[0];
    EXPECT_EQ(table.field(first, "name"), "a, b");
    EXPECT_EQ(table.field(first, "note"), "say \"hi\"\nbye");
    EXPECT_EQ(table.requiredNumber(first, "value"), 0.1);
    EXPECT_EQ(table.records()[1].line, 4U);
    EXPECT_FALSE(table.number(table.records()[1], "value").has_value());
}

TEST(Csv, ATruncatedRecordNamesItsLine) {
    try {
        (void)io::CsvTable::parse("a,b\n1,2\n3\n", "t.csv");
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_EQ(e.field(), "line 3");
        EXPECT_NE(e.detail().find("truncated"), std::string::npos) << e.detail();
    }
}

}  // namespace
}  // namespace paintlab
