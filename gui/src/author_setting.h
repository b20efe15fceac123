#pragma once
// The author stored with every version the workstation saves: asked once, at
// the first save (prefilled with the login name), remembered in QSettings
// ("author") and changed with Edit > Author....

#include <QString>

#include <optional>

class QWidget;

namespace paintlab::gui {

// The remembered author; empty until one was given.
QString rememberedAuthor();
void rememberAuthor(const QString& author);
// $USER, else $LOGNAME, else the home folder's name.
QString loginName();
// Asks for the author (dialog "author_dialog", prefilled with the remembered
// one or the login name) and remembers it; nullopt if cancelled or left empty.
std::optional<QString> askAuthor(QWidget* parent);
// The remembered author, or askAuthor() when there is none yet (the first save).
std::optional<QString> authorForSave(QWidget* parent);

}  // namespace paintlab::gui
