#pragma once
// A fresh temporary folder for one test (mkdtemp under $TMPDIR or /tmp),
// removed with everything in it when the test ends.

#include <stdlib.h>  // mkdtemp

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace paintlab::test {

// The names in a folder, sorted (a test that a writer left no temporary file).
inline std::vector<std::string> entriesOf(const std::filesystem::path& folder) {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(folder))
        names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

class TempDir {
public:
    TempDir() {
        const char* base = std::getenv("TMPDIR");  // NOLINT(concurrency-mt-unsafe)
        std::string pattern = (base != nullptr && *base != '\0' ? std::string(base) : std::string("/tmp"));
        pattern.append("/paintlab-test-XXXXXX");
        if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
        m_path = pattern;
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    TempDir(TempDir&&) = delete;
    TempDir& operator=(TempDir&&) = delete;
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(m_path, ec);
    }

    const std::filesystem::path& path() const { return m_path; }
    // The names in the folder, sorted: what a writer left behind.
    std::vector<std::string> entries() const { return entriesOf(m_path); }
    std::filesystem::path operator/(const std::string& name) const { return m_path / name; }
    // Writes text to a file in the folder; returns its path.
    std::filesystem::path write(const std::string& name, const std::string& text) const {
        auto file = m_path / name;
        std::ofstream(file, std::ios::binary) << text;
        return file;
    }

private:
    std::filesystem::path m_path;
};

}  // namespace paintlab::test
