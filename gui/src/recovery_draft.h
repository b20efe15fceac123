#pragma once
// The edited recipe's unsaved edits kept on disk, so that a crash or a kill
// loses at most the last kDelayMs of editing. While the document has unsaved
// edits, the draft is written (io/atomic_file.h: never half a file) at most
// kDelayMs after the first edit not yet written; once it has none (saved as
// a version, discarded, undone back to the saved state, another recipe
// loaded) the draft is removed. One draft per database, in the application's
// data folder (drafts/<hash of the database path>.json); the main window
// offers it back at the next start (restore or discard).

#include "recipe_document.h"

#include "paintlab/engine/recipe.h"

#include <QObject>
#include <QString>
#include <QTimer>

#include <filesystem>
#include <optional>

namespace paintlab::gui {

class RecoveryDraft : public QObject {
    Q_OBJECT
public:
    static constexpr int kDelayMs = 2000;

    struct Contents {
        Recipe recipe;
        QString origin;        // what the edits started from: "<name>, version 3" or a file
        int base_version = 0;  // the saved version the edits started from (0: none)
        QString written_at;    // ISO 8601 UTC
    };

    explicit RecoveryDraft(RecipeDocument* document, QObject* parent = nullptr);
    ~RecoveryDraft() override = default;
    RecoveryDraft(const RecoveryDraft&) = delete;
    RecoveryDraft& operator=(const RecoveryDraft&) = delete;
    RecoveryDraft(RecoveryDraft&&) = delete;
    RecoveryDraft& operator=(RecoveryDraft&&) = delete;

    // The database the drafts belong to; empty: no draft is kept.
    void setDatabase(const std::filesystem::path& database);
    // The draft file of the database set ("" if none).
    const QString& file() const { return m_file; }
    static QString fileFor(const std::filesystem::path& database);

    // The draft an earlier run left, if any. Throws InputError naming the
    // file if it cannot be read as a draft (truncated, not a recipe).
    std::optional<Contents> read() const;
    // Removes the draft and forgets the pending write.
    void remove();
    // Writes the draft now if the document has unsaved edits, else removes
    // it; false (and failed()) if it cannot be written.
    bool writeNow();

signals:
    // The draft could not be written (a full disk, no permission): the message names the file.
    void failed(const QString& message);

private:
    void documentChanged();

    RecipeDocument* m_document;
    QString m_file;
    QTimer m_timer;
};

}  // namespace paintlab::gui
