#include "author_setting.h"

#include <QCoreApplication>
#include <QDir>
#include <QInputDialog>
#include <QSettings>

namespace paintlab::gui {

namespace {
constexpr const char* kKey = "author";
}  // namespace

QString rememberedAuthor() { return QSettings().value(kKey).toString().trimmed(); }

void rememberAuthor(const QString& author) { QSettings().setValue(kKey, author.trimmed()); }

QString loginName() {
    for (const char* name : {"USER", "LOGNAME"}) {
        QString value = qEnvironmentVariable(name).trimmed();
        if (!value.isEmpty()) return value;
    }
    return QDir::home().dirName();
}

std::optional<QString> askAuthor(QWidget* parent) {
    const QString current = rememberedAuthor();
    QInputDialog dialog(parent);
    dialog.setObjectName("author_dialog");
    dialog.setWindowTitle(QCoreApplication::translate("Author", "Author"));
    dialog.setLabelText(
        QCoreApplication::translate("Author", "Your name, stored with every version you save:"));
    dialog.setTextValue(current.isEmpty() ? loginName() : current);
    // Modal: the save that asked waits for the name.
    if (dialog.exec() != QDialog::Accepted) return std::nullopt;
    const QString author = dialog.textValue().trimmed();
    if (author.isEmpty()) return std::nullopt;
    rememberAuthor(author);
    return author;
}

std::optional<QString> authorForSave(QWidget* parent) {
    const QString author = rememberedAuthor();
    if (!author.isEmpty()) return author;
    return askAuthor(parent);
}

}  // namespace paintlab::gui
