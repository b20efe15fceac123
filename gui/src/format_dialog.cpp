// File dialogs with the registry's formats (format_dialog.h).

#include "format_dialog.h"

#include <QFileDialog>
#include <QFileInfo>
#include <QSettings>

#include <algorithm>

namespace paintlab::gui {

namespace {

QString patterns(const std::vector<std::string>& extensions) {
    QStringList list;
    for (const auto& extension : extensions) list << "*" + QString::fromStdString(extension);
    return list.join(' ');
}

bool claims(const plugins::FormatInfo& format, const QString& path) {
    const QString suffix = "." + QFileInfo(path).suffix().toLower();
    return std::any_of(format.extensions.begin(), format.extensions.end(), [&](const std::string& extension) {
        return QString::fromStdString(extension) == suffix;
    });
}

std::optional<ChosenFile> runDialog(QWidget* parent, const QString& object_name, const QString& title,
                                    const QString& settings_key,
                                    const std::vector<plugins::FormatInfo>& formats, bool save) {
    const FormatFilters filters = formatFilters(formats, !save);
    QSettings settings;
    QFileDialog dialog(parent, title, settings.value(settings_key).toString());
    dialog.setObjectName(object_name);
    dialog.setAcceptMode(save ? QFileDialog::AcceptSave : QFileDialog::AcceptOpen);
    dialog.setFileMode(save ? QFileDialog::AnyFile : QFileDialog::ExistingFile);
    dialog.setNameFilters(filters.filters);
    if (dialog.exec() != QDialog::Accepted || dialog.selectedFiles().isEmpty()) return std::nullopt;
    ChosenFile chosen{dialog.selectedFiles().front(), std::nullopt};
    const plugins::FormatInfo* format = filters.formatOf(dialog.selectedNameFilter());
    if (save && QFileInfo(chosen.path).suffix().isEmpty()) {
        const plugins::FormatInfo* first = format != nullptr ? format
                                           : formats.empty() ? nullptr
                                                             : &formats.front();
        if (first != nullptr && !first->extensions.empty())
            chosen.path += QString::fromStdString(first->extensions.front());
    }
    if (format != nullptr && (!save || claims(*format, chosen.path))) chosen.format_id = format->id;
    settings.setValue(settings_key, QFileInfo(chosen.path).absolutePath());
    return chosen;
}

}  // namespace

const plugins::FormatInfo* FormatFilters::formatOf(const QString& filter) const {
    const auto i = filters.indexOf(filter);
    if (i < 0 || static_cast<std::size_t>(i) >= formats.size() || !formats[static_cast<std::size_t>(i)])
        return nullptr;
    return &*formats[static_cast<std::size_t>(i)];
}

FormatFilters formatFilters(const std::vector<plugins::FormatInfo>& formats, bool all_files) {
    FormatFilters result;
    std::vector<std::string> every;
    for (const auto& format : formats)
        for (const auto& extension : format.extensions)
            if (std::find(every.begin(), every.end(), extension) == every.end()) every.push_back(extension);
    result.filters << QFileDialog::tr("All supported (%1)").arg(patterns(every));
    result.formats.emplace_back();
    for (const auto& format : formats) {
        // ";;" separates filters: a description never holds it.
        const QString description = QString::fromStdString(format.description).replace(";;", "; ");
        const QString filter = QStringLiteral("%1 (%2)").arg(description, patterns(format.extensions));
        if (result.filters.contains(filter)) continue;  // the first format of that text keeps it
        result.filters << filter;
        result.formats.emplace_back(format);
    }
    if (all_files) {
        result.filters << QFileDialog::tr("All files (*)");
        result.formats.emplace_back();
    }
    return result;
}

std::optional<ChosenFile> chooseFileToOpen(QWidget* parent, const QString& object_name, const QString& title,
                                           const QString& settings_key,
                                           const std::vector<plugins::FormatInfo>& formats) {
    return runDialog(parent, object_name, title, settings_key, formats, false);
}

std::optional<ChosenFile> chooseFileToSave(QWidget* parent, const QString& object_name, const QString& title,
                                           const QString& settings_key,
                                           const std::vector<plugins::FormatInfo>& formats) {
    return runDialog(parent, object_name, title, settings_key, formats, true);
}

}  // namespace paintlab::gui
