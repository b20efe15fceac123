#include "recovery_draft.h"

#include "file_output.h"

#include "json_reader.h"
#include "paintlab/engine/error.h"
#include "paintlab/engine/recipe_json.h"

#include <QCryptographicHash>
#include <QDateTime>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QStandardPaths>
#include <QUndoStack>

#include <string>

namespace paintlab::gui {

namespace {
constexpr int kFormat = 1;
// A recipe is at most a few hundred kB (tabulated spectra); the draft adds a few lines.
constexpr std::size_t kMaxDraftBytes = 64u << 20u;
}  // namespace

RecoveryDraft::RecoveryDraft(RecipeDocument* document, QObject* parent)
    : QObject(parent), m_document(document) {
    m_timer.setSingleShot(true);
    m_timer.setInterval(kDelayMs);
    connect(&m_timer, &QTimer::timeout, this, &RecoveryDraft::writeNow);
    connect(document, &RecipeDocument::recipeChanged, this, &RecoveryDraft::documentChanged);
    connect(document->undoStack(), &QUndoStack::cleanChanged, this, &RecoveryDraft::documentChanged);
}

QString RecoveryDraft::fileFor(const std::filesystem::path& database) {
    const QString absolute = QFileInfo(QString::fromStdString(database.string())).absoluteFilePath();
    const QByteArray tag =
        QCryptographicHash::hash(absolute.toUtf8(), QCryptographicHash::Sha256).toHex().left(16);
    return QStandardPaths::writableLocation(QStandardPaths::AppDataLocation) + "/drafts/" +
           QString::fromLatin1(tag) + ".json";
}

void RecoveryDraft::setDatabase(const std::filesystem::path& database) {
    m_timer.stop();
    m_file = database.empty() ? QString() : fileFor(database);
}

void RecoveryDraft::documentChanged() {
    if (m_file.isEmpty()) return;
    if (!m_document->hasUnsavedEdits()) {
        remove();
    } else if (!m_timer.isActive()) {
        // Not restarted by later edits: a long drag is written every kDelayMs.
        m_timer.start();
    }
}

void RecoveryDraft::remove() {
    m_timer.stop();
    if (!m_file.isEmpty()) QFile::remove(m_file);
}

bool RecoveryDraft::writeNow() {
    m_timer.stop();
    if (m_file.isEmpty()) return false;
    if (!m_document->hasUnsavedEdits()) {
        remove();
        return true;
    }
    nlohmann::ordered_json draft;
    draft["draft_format"] = kFormat;
    draft["origin"] = m_document->origin().toStdString();
    draft["base_version"] = m_document->version();
    draft["written_at"] = QDateTime::currentDateTimeUtc().toString(Qt::ISODate).toStdString();
    draft["recipe"] = nlohmann::ordered_json::parse(recipeToJson(m_document->recipe()));
    QDir().mkpath(QFileInfo(m_file).absolutePath());
    if (!writeFileAtomically(m_file, draft.dump(1))) {
        emit failed(tr("Cannot write the recovery draft %1").arg(m_file));
        return false;
    }
    return true;
}

std::optional<RecoveryDraft::Contents> RecoveryDraft::read() const {
    if (m_file.isEmpty() || !QFile::exists(m_file)) return std::nullopt;
    const std::string source = m_file.toStdString();
    const nlohmann::json json =
        jsonio::parseUntrustedJson(jsonio::readBoundedTextFile(source, kMaxDraftBytes), source);
    if (!json.is_object()) throw InputError(source, "", "a recovery draft is a JSON object");
    jsonio::ObjectReader reader(json, "", source);
    if (reader.integerIn("draft_format", kFormat, kFormat) != kFormat)
        reader.fail("draft_format", "unknown draft format");
    Contents contents;
    contents.origin = QString::fromStdString(reader.string("origin", true));
    contents.base_version = reader.integerIn("base_version", 0, 1 << 30);
    contents.written_at = QString::fromStdString(reader.string("written_at", true));
    contents.recipe = parseRecipeJson(reader.require("recipe", "the edited recipe").dump(), source);
    reader.finish();
    return contents;
}

}  // namespace paintlab::gui
