#pragma once
// Text files compiled into the library (database/cmake/embed_text.cmake):
// the schema migrations and the demo data.

#include <initializer_list>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace paintlab::db::detail {

struct EmbeddedFile {
    std::string name;  // file name without folder: "0001_initial.sql"
    std::string text;
};

// The generated sources list each file as chunks of raw string literals.
struct EmbeddedChunks {
    std::string_view name;
    std::span<const std::string_view> chunks;
};
std::vector<EmbeddedFile> joinChunks(std::initializer_list<EmbeddedChunks> files);

// Schema migrations in order: file i brings the schema to version i + 1.
const std::vector<EmbeddedFile>& migrationFiles();
// demo-ingredients.json, then the demo recipe files.
const std::vector<EmbeddedFile>& demoFiles();

}  // namespace paintlab::db::detail
