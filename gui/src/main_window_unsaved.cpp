// Work is never lost (issue 27): before the edited recipe is replaced (another
// recipe picked, a file or a version opened) or the window closed, unsaved
// edits are saved as a version, discarded, or the step is cancelled; a
// recovery draft written a few seconds after each edit is offered back at
// the next start after a crash or a kill.
//
// These questions are modal (exec()): what follows (closing the window,
// loading the other recipe) depends on the answer, as in every document
// application. Renders and plots still arrive meanwhile; the recipe cannot
// be edited while a question is open.

#include "main_window.h"

#include "replace_recipe_command.h"

#include "paintlab/database/recipes.h"

#include <QDateTime>
#include <QInputDialog>
#include <QListWidget>
#include <QMessageBox>
#include <QPushButton>
#include <QStatusBar>
#include <QUndoStack>

#include <exception>

namespace paintlab::gui {

bool MainWindow::resolveUnsavedEdits(const QString& next_step) {
    if (!m_document.hasUnsavedEdits()) return true;
    QMessageBox box(
        QMessageBox::Question, tr("Unsaved edits"),
        tr("<b>%1</b> has edits that are not saved as a version.").arg(currentLabel().toHtmlEscaped()),
        QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel, this);
    box.setObjectName("unsaved_question");
    box.setInformativeText(tr("Save them as a new version before %1?").arg(next_step));
    box.button(QMessageBox::Save)->setText(m_db ? tr("Save version...") : tr("Save version (no database)"));
    box.button(QMessageBox::Save)->setEnabled(m_db.has_value());
    box.button(QMessageBox::Discard)->setText(tr("Discard edits"));
    box.setDefaultButton(m_db ? QMessageBox::Save : QMessageBox::Cancel);
    box.setEscapeButton(QMessageBox::Cancel);
    switch (box.exec()) {
    case QMessageBox::Save:
        return saveVersion();
    case QMessageBox::Discard:
        m_draft.remove();
        return true;
    default:
        return false;
    }
}

bool MainWindow::saveVersion() {
    if (!m_db || !m_document.hasRecipe()) return false;
    QInputDialog dialog(this);
    dialog.setObjectName("version_note_dialog");
    dialog.setWindowTitle(tr("Save version"));
    dialog.setLabelText(tr("What changed and why:"));
    if (dialog.exec() != QDialog::Accepted) return false;
    return saveVersionAs(dialog.textValue());
}

void MainWindow::pickRecipe(const QString& name) {
    // Until answered, the list shows the recipe being edited.
    if (m_document.hasRecipe()) selectListItem(QString::fromStdString(m_document.recipe().name));
    if (resolveUnsavedEdits(tr("opening %1").arg(name))) selectRecipe(name);
}

bool MainWindow::offerRecoveredDraft() {
    std::optional<RecoveryDraft::Contents> draft;
    try {
        draft = m_draft.read();
    } catch (const std::exception& e) {
        // Unreadable (cut short by a full disk): say so and keep the file for a look.
        statusBar()->showMessage(tr("Recovery draft not usable: %1").arg(QString::fromUtf8(e.what())));
        return false;
    }
    if (!draft) return false;
    QMessageBox box(QMessageBox::Question, tr("Recover unsaved edits"),
                    tr("PaintLab was not closed normally and kept unsaved edits of <b>%1</b> "
                       "(from %2, written %3 UTC).")
                        .arg(QString::fromStdString(draft->recipe.name).toHtmlEscaped(),
                             draft->origin.toHtmlEscaped(),
                             QDateTime::fromString(draft->written_at, Qt::ISODate)
                                 .toString(QStringLiteral("yyyy-MM-dd HH:mm:ss"))),
                    QMessageBox::Discard, this);
    box.setObjectName("recovery_question");
    box.setInformativeText(tr("Restore them to go on editing, or discard them?"));
    QPushButton* restore = box.addButton(tr("Restore"), QMessageBox::AcceptRole);
    box.button(QMessageBox::Discard)->setText(tr("Discard edits"));
    box.setDefaultButton(restore);
    box.setEscapeButton(QMessageBox::Discard);
    box.exec();
    if (box.clickedButton() != restore) {
        m_draft.remove();
        return false;
    }
    // Over the version the edits started from, when it is still there: undo leads back to it.
    const QString name = QString::fromStdString(draft->recipe.name);
    bool based = false;
    if (m_db && draft->base_version > 0) {
        try {
            const db::StoredRecipeVersion base =
                db::loadRecipeVersion(*m_db, draft->recipe.name, draft->base_version);
            m_document.load(base.recipe, tr("%1, version %2").arg(name).arg(draft->base_version),
                            draft->base_version);
            based = true;
        } catch (const std::exception&) {
            // The version is gone (another database file at that path): the edits alone.
        }
    }
    if (based) {
        m_document.undoStack()->push(
            new ReplaceRecipeCommand(&m_document, draft->recipe, tr("Recovered edits")));
    } else {
        m_document.load(draft->recipe, draft->origin, 0);
        m_document.undoStack()->resetClean();  // unsaved: asked about before it is dropped
    }
    selectListItem(name);
    m_draft.writeNow();  // load() removed the file: the restored edits are on disk again at once
    statusBar()->showMessage(tr("Restored the unsaved edits of %1").arg(name));
    return true;
}

}  // namespace paintlab::gui
