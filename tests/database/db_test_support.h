#pragma once
// Helpers of the database tests: a temporary folder, raw SQLite access
// (to play another program or a tamperer), file bytes, a small valid recipe.

#include "paintlab/engine/recipe.h"
#include "paintlab/engine/recipe_json.h"

#include "temp_dir.h"

#include <gtest/gtest.h>
#include <sqlite3.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace paintlab::db::test {

using paintlab::test::TempDir;

inline std::string fileBytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::string bytes(static_cast<std::size_t>(std::filesystem::file_size(path)), '\0');
    in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return bytes;
}

inline void writeBytes(const std::filesystem::path& path, const std::string& bytes,
                       std::streamoff offset = -1) {
    if (offset < 0) {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out << bytes;
        return;
    }
    std::fstream out(path, std::ios::binary | std::ios::in | std::ios::out);
    out.seekp(offset);
    out << bytes;
}

// Runs SQL on its own connection (no PaintLab code involved); returns the
// SQLite result code and puts SQLite's message in error.
inline int rawExec(const std::filesystem::path& file, const std::string& sql, std::string* error = nullptr) {
    sqlite3* db = nullptr;
    int rc = sqlite3_open_v2(file.c_str(), &db, SQLITE_OPEN_READWRITE, nullptr);
    if (rc == SQLITE_OK) {
        char* message = nullptr;
        rc = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &message);
        if (error != nullptr) *error = message != nullptr ? message : "";
        sqlite3_free(message);
    }
    sqlite3_close(db);
    return rc;
}

// The first column of the first row of a query, as text ("" if none).
inline std::string rawQuery(const std::filesystem::path& file, const std::string& sql) {
    sqlite3* db = nullptr;
    std::string out;
    if (sqlite3_open_v2(file.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) == SQLITE_OK) {
        sqlite3_stmt* stmt = nullptr;
        if (sqlite3_prepare_v2(db, sql.c_str(), -1, &stmt, nullptr) == SQLITE_OK &&
            sqlite3_step(stmt) == SQLITE_ROW) {
            const unsigned char* text = sqlite3_column_text(stmt, 0);
            if (text != nullptr) out = reinterpret_cast<const char*>(text);
        }
        sqlite3_finalize(stmt);
    }
    sqlite3_close(db);
    return out;
}

// tests/data/valid_minimal.json ("test basecoat": binder 'acrylic', pigment 'red', mirror flake 'aluminium').
inline Recipe minimalRecipe(const std::string& name = "test basecoat", double thickness_um = 20.0) {
    Recipe recipe = loadRecipeFile(std::filesystem::path(PAINTLAB_TEST_DATA_DIR) / "valid_minimal.json");
    recipe.name = name;
    recipe.layers.at(0).thickness_um = thickness_um;
    return recipe;
}

}  // namespace paintlab::db::test
