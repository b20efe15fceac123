// Bad colord data: PAINTLAB_COLORD_DIR pointed at a scratch directory holding
// missing, truncated, garbage or inconsistent tables must give a
// paintlab::Error that names the file, never a crash or a silent wrong table.

#include "paintlab/engine/colour/cie_tables.h"
#include "paintlab/engine/error.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <sstream>
#include <string>
#include <unistd.h>

namespace paintlab {
namespace {

namespace fs = std::filesystem;

const fs::path kRealCmf = fs::path("/usr/share/colord") / "cmf" / "CIE1931-2deg-XYZ.cmf";

std::string readText(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

void writeText(const fs::path& file, const std::string& text) {
    fs::create_directories(file.parent_path());
    std::ofstream out(file, std::ios::binary);
    out << text;
}

// Runs call, which must throw paintlab::Error whose message names file and contains detail.
void expectErrorNaming(const std::function<void()>& call, const fs::path& file, const std::string& detail) {
    try {
        call();
        ADD_FAILURE() << "no paintlab::Error for " << file;
    } catch (const Error& error) {
        const std::string message = error.what();
        EXPECT_NE(message.find(file.string()), std::string::npos) << message;
        EXPECT_NE(message.find(detail), std::string::npos) << message;
    }
}

// A scratch colord directory, named in PAINTLAB_COLORD_DIR for the test's duration.
class BadColordData : public ::testing::Test {
protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        m_dir = fs::temp_directory_path() /
                ("paintlab_colord_" + std::to_string(::getpid()) + "_" + info->name());
        fs::remove_all(m_dir);
        fs::create_directories(m_dir / "cmf");
        if (const char* previous = std::getenv("PAINTLAB_COLORD_DIR")) m_previous = previous;
        ::setenv("PAINTLAB_COLORD_DIR", m_dir.c_str(), 1);
    }

    void TearDown() override {
        if (m_previous)
            ::setenv("PAINTLAB_COLORD_DIR", m_previous->c_str(), 1);
        else
            ::unsetenv("PAINTLAB_COLORD_DIR");
        std::error_code ignored;
        fs::remove_all(m_dir, ignored);
    }

    // Writes text as the 2 degree CMF file and returns its path, resolved through the variable.
    fs::path writeCmf(const std::string& text) const {
        fs::path file = cmfFilePath(Observer::Cie1931_2deg);
        writeText(file, text);
        return file;
    }

    fs::path m_dir;
    std::optional<std::string> m_previous;
};

TEST_F(BadColordData, EnvironmentVariableSelectsTheDirectory) {
    EXPECT_EQ(colordDataDir(), m_dir);
    EXPECT_EQ(cmfFilePath(Observer::Cie1964_10deg), m_dir / "cmf" / "CIE1964-10deg-XYZ.cmf");
    EXPECT_EQ(illuminantFilePath(Illuminant::D50), m_dir / "illuminant" / "CIE-D50.sp");
    ::setenv("PAINTLAB_COLORD_DIR", "", 1);  // empty means unset: the Debian default
    EXPECT_EQ(colordDataDir(), fs::path("/usr/share/colord"));
}

TEST_F(BadColordData, ACopyOfTheRealFileReadsIdentically) {
    // The control: the scratch directory itself is not what the other tests trip on.
    const fs::path file = writeCmf(readText(kRealCmf));
    const ColourMatchingFunctions copy = readCmfFile(file);
    EXPECT_EQ(copy.yBar, readCmfFile(kRealCmf).yBar);
}

TEST_F(BadColordData, MissingFile) {
    const fs::path file = cmfFilePath(Observer::Cie1931_2deg);
    expectErrorNaming([&] { readCmfFile(file); }, file, "cannot read CIE table");
}

TEST_F(BadColordData, EmptyFile) {
    const fs::path file = writeCmf("");
    expectErrorNaming([&] { readCmfFile(file); }, file, "is empty");
}

TEST_F(BadColordData, TruncatedInTheDataBlock) {
    const std::string real = readText(kRealCmf);
    // Cut in the middle of the second data set (the y-bar row).
    const fs::path file = writeCmf(real.substr(0, real.rfind("BEGIN_DATA") + 2000));
    expectErrorNaming([&] { readCmfFile(file); }, file, "(truncated?)");
}

TEST_F(BadColordData, TruncatedInTheHeader) {
    const std::string real = readText(kRealCmf);
    const fs::path file = writeCmf(real.substr(0, real.find("BEGIN_DATA_FORMAT") + 200));
    expectErrorNaming([&] { readCmfFile(file); }, file, "not a readable CGATS/IT8 file: line ");
}

TEST_F(BadColordData, MissingValuesBeforeEndData) {
    std::string text = readText(kRealCmf);
    // Drop the last z-bar value but keep END_DATA: the count check must catch it.
    const std::size_t end = text.rfind("\nEND_DATA");
    const std::size_t lastTab = text.rfind('\t', end);
    text.erase(lastTab, end - lastTab);
    const fs::path file = writeCmf(text);
    expectErrorNaming([&] { readCmfFile(file); }, file, "data block has 284 values, expected 3 sets of 95");
}

TEST_F(BadColordData, GarbageText) {
    const fs::path file = writeCmf("this is not a colour matching function\nat all\n");
    expectErrorNaming([&] { readCmfFile(file); }, file, "not a readable CGATS/IT8 file");
}

TEST_F(BadColordData, BinaryGarbage) {
    std::string bytes;
    for (int i = 0; i < 4096; ++i) bytes.push_back(static_cast<char>((i * 7919) % 251));
    const fs::path file = writeCmf(bytes);
    expectErrorNaming([&] { readCmfFile(file); }, file, "is not a text file");
}

TEST_F(BadColordData, NonNumericValueIsReportedWithItsField) {
    std::string text = readText(kRealCmf);
    const std::size_t at = text.find("0.0001299");
    text.replace(at, 9, "O.0001299");  // letter O for zero, a classic
    const fs::path file = writeCmf(text);
    // The first value of colord's file: data set 1, field SPEC_360.
    expectErrorNaming([&] { readCmfFile(file); }, file,
                      "data set 1, SPEC_360: 'O.0001299' is not a finite number");
}

TEST_F(BadColordData, ASplitValueIsReportedWithItsLine) {
    std::string text = readText(kRealCmf);
    text.replace(text.find("0.0001299"), 9, "0.00 1299");  // one value too many
    const fs::path file = writeCmf(text);
    expectErrorNaming([&] { readCmfFile(file); }, file, "not a readable CGATS/IT8 file: line ");
}

TEST_F(BadColordData, NegativeValue) {
    std::string text = readText(kRealCmf);
    text.replace(text.find("0.0001299"), 9, "-0.0001299");
    const fs::path file = writeCmf(text);
    expectErrorNaming([&] { readCmfFile(file); }, file, "negative value");
}

TEST_F(BadColordData, HeaderDisagreesWithTheData) {
    std::string text = readText(kRealCmf);
    text.replace(text.find("SPECTRAL_BANDS\t95"), 17, "SPECTRAL_BANDS\t96");
    const fs::path file = writeCmf(text);
    expectErrorNaming([&] { readCmfFile(file); }, file, "differs from SPECTRAL_BANDS");
}

TEST_F(BadColordData, IlluminantFileWhereObserverExpected) {
    // One data set where three are needed: the wrong file under the right name.
    const fs::path file = writeCmf(readText(fs::path("/usr/share/colord") / "illuminant" / "CIE-D65.sp"));
    expectErrorNaming([&] { readCmfFile(file); }, file, "has 1 data sets, expected 3");
}

TEST_F(BadColordData, CachedAccessorReportsTheFileAndRetriesDeathTest) {
    // cmf() caches in a function-local static; this process may have loaded the good table
    // already, so check the cached path in a freshly executed child ("threadsafe" death
    // tests re-run the binary for this test alone).
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    EXPECT_EXIT(
        {
            const fs::path file = writeCmf("CMF\nSPECTRAL_START_NM\t360.0\n");
            for (int attempt = 0; attempt < 2; ++attempt) {  // a failed load is not cached
                try {
                    cmf(Observer::Cie1931_2deg);
                    std::exit(3);
                } catch (const Error& error) {
                    if (std::string(error.what()).find(file.string()) == std::string::npos) std::exit(4);
                }
            }
            writeCmf(readText(kRealCmf));  // repaired: the next call loads it
            std::exit(cmf(Observer::Cie1931_2deg).yBar(555.0) == 1.0 ? 0 : 5);
        },
        ::testing::ExitedWithCode(0), "");
}

}  // namespace
}  // namespace paintlab
