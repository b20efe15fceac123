#pragma once
// File dialogs whose formats come from the plugin registry
// (plugins/exchange.h): "All supported (...)" first, then one name filter per
// format (its description and extensions), then "All files (*)" when
// opening. The filter chosen names the format (its id); "All supported" and
// "All files" leave the choice to the registry (extension, then content). No
// format is named here: a plugin's new format appears in every dialog of its
// kind without a change to the GUI.

#include "paintlab/plugins/plugin.h"

#include <QString>
#include <QStringList>

#include <optional>
#include <string>
#include <vector>

class QWidget;

namespace paintlab::gui {

struct FormatFilters {
    QStringList filters;
    // Per filter: the format it names; nullopt for "All supported" and "All files".
    std::vector<std::optional<plugins::FormatInfo>> formats;
    // The format a filter names (nullptr: the registry chooses).
    const plugins::FormatInfo* formatOf(const QString& filter) const;
};

// The filters of these formats (in their order); `all_files` adds "All files (*)" last.
FormatFilters formatFilters(const std::vector<plugins::FormatInfo>& formats, bool all_files);

struct ChosenFile {
    QString path;
    std::optional<std::string> format_id;  // nullopt: by the file's extension and content
};

// A modal file dialog (Qt's own or the platform's) named `object_name`
// (tests answer it), starting in the folder last used under `settings_key`
// (QSettings; remembered when a file is chosen). nullopt if cancelled.
std::optional<ChosenFile> chooseFileToOpen(QWidget* parent, const QString& object_name, const QString& title,
                                           const QString& settings_key,
                                           const std::vector<plugins::FormatInfo>& formats);
// As chooseFileToOpen, for a file to write. A name typed without an
// extension takes the chosen format's first one ("All supported": the first
// format's); a name whose extension the chosen format does not claim is
// left to the registry (the name typed wins over the filter).
std::optional<ChosenFile> chooseFileToSave(QWidget* parent, const QString& object_name, const QString& title,
                                           const QString& settings_key,
                                           const std::vector<plugins::FormatInfo>& formats);

}  // namespace paintlab::gui
