// What a lab database must survive: a writer killed with SIGKILL mid-write,
// a reader running while a writer saves, another program holding the write
// lock, a read-only file, a full disk. Each failure is a clear error naming
// the file, and nothing already saved is lost.

#include "db_test_support.h"

#include "paintlab/database/ingredients.h"
#include "paintlab/database/recipes.h"

#include <gtest/gtest.h>

#include <atomic>
#include <csignal>
#include <cstring>
#include <sys/resource.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace paintlab::db {
namespace {

using test::TempDir;

// Version v of the test recipe has a basecoat of this thickness, so every
// loaded version can be checked against what was saved.
double thicknessOfVersion(int version) { return 10.0 + 0.125 * version; }

SaveOptions writer() { return {"writer", "", false, "test"}; }

// Runs body in a forked child and returns what it wrote to the pipe. The
// child never returns into GoogleTest.
template <class Body> std::string inChild(Body body, int* status_out = nullptr) {
    int fds[2];
    if (pipe(fds) != 0) throw std::runtime_error("pipe failed");
    const pid_t pid = fork();
    if (pid == 0) {
        close(fds[0]);
        int code = 0;
        try {
            std::string report = body();
            if (write(fds[1], report.data(), report.size()) < 0) code = 4;
        } catch (const std::exception& e) {
            const std::string report = std::string("exception: ") + e.what();
            if (write(fds[1], report.data(), report.size()) < 0) code = 4;
            code = 3;
        }
        close(fds[1]);
        _exit(code);
    }
    close(fds[1]);
    std::string out;
    char buffer[4096];
    for (ssize_t n = 0; (n = read(fds[0], buffer, sizeof buffer)) > 0;)
        out.append(buffer, static_cast<std::size_t>(n));
    close(fds[0]);
    int status = 0;
    waitpid(pid, &status, 0);
    if (status_out != nullptr) *status_out = status;
    return out;
}

TEST(Reliability, SigkillDuringWritesLosesNoCommittedVersion) {
    TempDir dir;
    const auto file = dir / "killed.db";
    Database::open(file);  // created before the child, so both agree on the schema
    int fds[2];
    ASSERT_EQ(pipe(fds), 0);
    const pid_t pid = fork();
    if (pid == 0) {
        close(fds[0]);
        try {
            Database db = Database::open(file);
            for (int v = 1; v < 100000; ++v) {
                Ingredient ing;  // an ingredient per version too: more writes in flight when the kill comes
                ing.name = "binder " + std::to_string(v);
                ing.data = Binder{ing.name, Spectrum({380, 780}, {1.5, 1.49}), Spectrum(0.0)};
                createIngredient(db, ing);
                const auto saved =
                    saveRecipeVersion(db, test::minimalRecipe("killed", thicknessOfVersion(v)), writer());
                // Acknowledge only after the commit returned.
                if (write(fds[1], &saved.version, sizeof saved.version) < 0) _exit(4);
            }
        } catch (...) {
            _exit(3);
        }
        _exit(0);
    }
    close(fds[1]);
    int acknowledged = 0;
    int version = 0;
    while (acknowledged < 25 && read(fds[0], &version, sizeof version) == sizeof version)
        acknowledged = version;
    usleep(3000);  // land the kill somewhere inside a later transaction
    kill(pid, SIGKILL);
    int status = 0;
    waitpid(pid, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << "the writer stopped before the kill";
    while (read(fds[0], &version, sizeof version) == sizeof version) acknowledged = version;
    close(fds[0]);
    ASSERT_GE(acknowledged, 25);

    Database db = Database::open(file);
    EXPECT_TRUE(db.integrityCheck().empty());
    const auto history = recipeHistory(db, "killed");
    ASSERT_GE(static_cast<int>(history.size()), acknowledged);
    EXPECT_LE(static_cast<int>(history.size()), acknowledged + 1);  // the one in flight may have committed
    for (int v = 1; v <= static_cast<int>(history.size()); ++v) {
        const auto stored = loadRecipeVersion(db, "killed", v);
        EXPECT_EQ(stored.recipe.layers.at(0).thickness_um, thicknessOfVersion(v)) << "version " << v;
        EXPECT_TRUE(findIngredient(db, IngredientKind::Binder, "binder " + std::to_string(v))) << v;
    }
    // Still writable after recovery.
    EXPECT_TRUE(saveRecipeVersion(db, test::minimalRecipe("killed", 99.0), writer()).created);
}

TEST(Reliability, ReaderNeverSeesHalfARecipe) {
    TempDir dir;
    const auto file = dir / "concurrent.db";
    // Versions alternate between one and three layers: a half-saved version
    // would show a JSON / row mismatch or a bad checksum.
    auto recipeOfVersion = [](int v) {
        Recipe recipe = test::minimalRecipe("shared", thicknessOfVersion(v));
        for (int extra = 0; extra < (v % 2 == 0 ? 2 : 0); ++extra) recipe.layers.push_back(recipe.layers[0]);
        return recipe;
    };
    {
        Database db = Database::open(file);
        saveRecipeVersion(db, recipeOfVersion(1), writer());
    }
    constexpr int kVersions = 60;
    std::atomic<bool> done{false};
    std::atomic<int> reads{0};
    std::string reader_failure;
    std::thread reader([&] {
        try {
            Database db = Database::open(file);
            while (!done.load()) {
                const auto stored = loadRecipeVersion(db, "shared");
                const Recipe expected = recipeOfVersion(stored.info.version);
                if (stored.recipe != expected || stored.layers.size() != expected.layers.size()) {
                    reader_failure = "version " + std::to_string(stored.info.version) + " read inconsistent";
                    return;
                }
                for (const auto& layer : stored.layers)
                    if (layer.components.size() != 2) reader_failure = "a layer without its components";
                ++reads;
            }
        } catch (const std::exception& e) {
            reader_failure = e.what();
        }
    });
    {
        Database db = Database::open(file);
        for (int v = 2; v <= kVersions; ++v) saveRecipeVersion(db, recipeOfVersion(v), writer());
    }
    done = true;
    reader.join();
    EXPECT_EQ(reader_failure, "");
    EXPECT_GT(reads.load(), 0);
    Database db = Database::open(file);
    EXPECT_EQ(recipeHistory(db, "shared").size(), static_cast<std::size_t>(kVersions));
}

TEST(Reliability, LockedDatabaseGivesAClearErrorAndLosesNothing) {
    TempDir dir;
    const auto file = dir / "locked.db";
    OpenOptions quick;
    quick.busy_timeout_ms = 100;
    Database db = Database::open(file, quick);
    saveRecipeVersion(db, test::minimalRecipe("r", 20.0), writer());

    sqlite3* other = nullptr;  // another program holding a write transaction
    ASSERT_EQ(sqlite3_open(file.c_str(), &other), SQLITE_OK);
    ASSERT_EQ(sqlite3_exec(other, "BEGIN IMMEDIATE; INSERT INTO tag (name) VALUES ('held')", nullptr, nullptr,
                           nullptr),
              SQLITE_OK);
    try {
        saveRecipeVersion(db, test::minimalRecipe("r", 21.0), writer());
        ADD_FAILURE() << "saved while another connection held the write lock";
    } catch (const DatabaseError& e) {
        EXPECT_EQ(e.reason(), DatabaseError::Reason::Busy);
        EXPECT_FALSE(e.isBadFile());
        EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("locked"), std::string::npos) << e.what();
    }
    EXPECT_EQ(loadRecipeVersion(db, "r").info.version, 1);  // reading still works (WAL)
    ASSERT_EQ(sqlite3_exec(other, "COMMIT", nullptr, nullptr, nullptr), SQLITE_OK);
    sqlite3_close(other);

    EXPECT_EQ(saveRecipeVersion(db, test::minimalRecipe("r", 21.0), writer()).version, 2);
    EXPECT_EQ(loadRecipeVersion(db, "r", 1).recipe, test::minimalRecipe("r", 20.0));
}

TEST(Reliability, ReadOnlyFileCanBeReadNotWritten) {
    TempDir dir;
    const auto file = dir / "readonly.db";
    {
        Database db = Database::open(file);
        saveRecipeVersion(db, test::minimalRecipe("r", 20.0), writer());
    }
    const std::string before = test::fileBytes(file);
    // The folder stays writable (SQLite keeps its -shm there); only the file is read-only.
    std::filesystem::permissions(dir.path(), std::filesystem::perms::all);
    std::filesystem::permissions(file, std::filesystem::perms::owner_read |
                                           std::filesystem::perms::group_read |
                                           std::filesystem::perms::others_read);
    const std::string report = inChild([&] {
        // root ignores file permissions: play an ordinary user.
        if (geteuid() == 0 && (setgid(65534) != 0 || setuid(65534) != 0)) return std::string("setuid failed");
        Database db = Database::open(file);
        std::string out = db.isReadOnly() ? "readonly;" : "writable;";
        out += "read v" + std::to_string(loadRecipeVersion(db, "r").info.version) + ";";
        try {
            saveRecipeVersion(db, test::minimalRecipe("r", 30.0), writer());
            out += "saved";
        } catch (const DatabaseError& e) {
            out += std::string(e.reason() == DatabaseError::Reason::ReadOnly ? "ReadOnly: " : "other: ") +
                   e.what();
        }
        try {
            Ingredient ing;
            ing.name = "b";
            ing.data = Binder{};
            createIngredient(db, ing);
            out += ";created";
        } catch (const DatabaseError& e) {
            out += std::string(e.reason() == DatabaseError::Reason::ReadOnly ? ";ReadOnly2" : ";other2: ") +
                   e.what();
        }
        return out;
    });
    EXPECT_NE(report.find("readonly;read v1;ReadOnly: "), std::string::npos) << report;
    EXPECT_NE(report.find(file.string()), std::string::npos) << report;
    EXPECT_NE(report.find("read-only"), std::string::npos) << report;
    EXPECT_NE(report.find(";ReadOnly2"), std::string::npos) << report;
    EXPECT_EQ(test::fileBytes(file), before);

    std::filesystem::permissions(file,
                                 std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
    Database db = Database::open(file);
    EXPECT_EQ(recipeHistory(db, "r").size(), 1U);
}

TEST(Reliability, FullDiskGivesAClearErrorAndLosesNothing) {
    TempDir dir;
    const auto file = dir / "full.db";
    {
        Database db = Database::open(file);
        for (int v = 1; v <= 3; ++v)
            saveRecipeVersion(db, test::minimalRecipe("r", thicknessOfVersion(v)), writer());
    }
    const auto limit = static_cast<rlim_t>(std::filesystem::file_size(file) + 16384);
    int status = 0;
    const std::string report = inChild(
        [&] {
            // The file size limit stands in for a full disk; SIGXFSZ would kill the process instead of
            // failing write().
            std::signal(SIGXFSZ, SIG_IGN);
            const rlimit rl{limit, limit};
            if (setrlimit(RLIMIT_FSIZE, &rl) != 0) return std::string("setrlimit failed");
            Database db = Database::open(file);
            Recipe big = test::minimalRecipe("r", thicknessOfVersion(4));
            big.description = std::string(400000, 'x');  // far more than the limit allows
            try {
                saveRecipeVersion(db, big, writer());
                return std::string("saved");
            } catch (const DatabaseError& e) {
                const bool full =
                    e.reason() == DatabaseError::Reason::Full || e.reason() == DatabaseError::Reason::Io;
                return std::string(full ? "full: " : "other: ") + e.what();
            }
        },
        &status);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << report;
    EXPECT_EQ(report.rfind("full: ", 0), 0U) << report;
    EXPECT_NE(report.find(file.string()), std::string::npos) << report;
    EXPECT_NE(report.find("disk"), std::string::npos) << report;

    Database db = Database::open(file);
    EXPECT_TRUE(db.integrityCheck().empty());
    const auto history = recipeHistory(db, "r");
    ASSERT_EQ(history.size(), 3U);
    for (int v = 1; v <= 3; ++v)
        EXPECT_EQ(loadRecipeVersion(db, "r", v).recipe.layers.at(0).thickness_um, thicknessOfVersion(v));
}

}  // namespace
}  // namespace paintlab::db
