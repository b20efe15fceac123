#include "versions_dock.h"

#include "author_setting.h"

#include <QHBoxLayout>
#include <QHeaderView>
#include <QInputDialog>
#include <QLabel>
#include <QMessageBox>
#include <QPushButton>
#include <QSplitter>
#include <QTableWidget>
#include <QVBoxLayout>

#include <algorithm>
#include <exception>

namespace paintlab::gui {

namespace {

QString qs(const std::string& s) { return QString::fromStdString(s); }

QTableWidget* makeTable(const QStringList& headers, QWidget* parent) {
    auto* table = new QTableWidget(0, static_cast<int>(headers.size()), parent);
    table->setHorizontalHeaderLabels(headers);
    table->setSelectionBehavior(QAbstractItemView::SelectRows);
    table->setEditTriggers(QAbstractItemView::NoEditTriggers);
    table->verticalHeader()->hide();
    table->horizontalHeader()->setStretchLastSection(true);
    table->setWordWrap(false);
    return table;
}

}  // namespace

VersionsDock::VersionsDock(RecipeDocument* document, QWidget* parent)
    : QDockWidget(tr("Recipe versions"), parent), m_document(document) {
    setObjectName("versions");
    auto* body = new QWidget(this);
    auto* layout = new QVBoxLayout(body);
    m_title = new QLabel(body);
    m_title->setObjectName("versions_title");
    m_title->setWordWrap(true);
    layout->addWidget(m_title);

    auto* split = new QSplitter(Qt::Vertical, body);
    m_table = makeTable({tr("Version"), tr("Author"), tr("Saved (UTC)"), tr("Note")}, split);
    m_table->setObjectName("version_history");
    m_table->setSelectionMode(QAbstractItemView::ExtendedSelection);
    m_table->setToolTip(tr("Select two versions to compare them; double-click one to open it"));
    split->addWidget(m_table);
    auto* diff_box = new QWidget(split);
    auto* diff_layout = new QVBoxLayout(diff_box);
    diff_layout->setContentsMargins(0, 0, 0, 0);
    m_diff_title = new QLabel(tr("Select two versions and press Compare"), diff_box);
    m_diff_title->setObjectName("diff_title");
    m_diff_table = makeTable({tr("Parameter"), tr("Old"), tr("New")}, diff_box);
    m_diff_table->setObjectName("version_diff");
    m_diff_table->setSelectionMode(QAbstractItemView::ContiguousSelection);
    diff_layout->addWidget(m_diff_title);
    diff_layout->addWidget(m_diff_table, 1);
    split->addWidget(diff_box);
    layout->addWidget(split, 1);

    auto* buttons = new QHBoxLayout;
    m_save = new QPushButton(tr("Save version..."), body);
    m_save->setToolTip(tr("Save the edited recipe as a new version, with a note"));
    m_compare = new QPushButton(tr("Compare"), body);
    m_compare->setToolTip(tr("The values that changed between the two selected versions "
                             "(one selected: from the version before it)"));
    m_open = new QPushButton(tr("Open"), body);
    m_open->setToolTip(tr("Edit the selected version"));
    m_revert = new QPushButton(tr("Revert to"), body);
    m_revert->setToolTip(tr("Save the selected version's contents as a new version (versions never change)"));
    m_compare_render = new QPushButton(tr("Compare in render"), body);
    m_compare_render->setObjectName("compare_in_render");
    m_compare_render->setToolTip(tr("Render the selected version beside the edited recipe (the render "
                                    "view: side by side or split)"));
    // Two rows, so the dock fits a 340-pixel column: versions, then comparisons.
    for (QPushButton* b : {m_save, m_open, m_revert}) buttons->addWidget(b);
    buttons->addStretch(1);
    layout->addLayout(buttons);
    auto* compare_row = new QHBoxLayout;
    for (QPushButton* b : {m_compare, m_compare_render}) compare_row->addWidget(b);
    compare_row->addStretch(1);
    layout->addLayout(compare_row);
    setWidget(body);

    connect(m_save, &QPushButton::clicked, this, &VersionsDock::askNoteAndSave);
    connect(m_compare, &QPushButton::clicked, this, &VersionsDock::diffSelected);
    connect(m_open, &QPushButton::clicked, this, [this]() {
        const std::vector<int> v = selectedVersions();
        if (!v.empty() && mayLeave(tr("opening version %1").arg(v.back()))) openVersion(v.back());
    });
    connect(m_revert, &QPushButton::clicked, this, &VersionsDock::revertSelected);
    connect(m_compare_render, &QPushButton::clicked, this, [this]() {
        const std::vector<int> v = selectedVersions();
        if (v.size() == 1) compareInRender(v.front());
    });
    connect(m_table, &QTableWidget::itemSelectionChanged, this, &VersionsDock::updateButtons);
    // Queued: opening a version refills the table whose signal this is.
    connect(
        m_table, &QTableWidget::cellDoubleClicked, this,
        [this](int row) {
            if (row < 0 || row >= static_cast<int>(m_history.size())) return;
            const int version = m_history[static_cast<std::size_t>(row)].version;
            if (mayLeave(tr("opening version %1").arg(version))) openVersion(version);
        },
        Qt::QueuedConnection);
    connect(document, &RecipeDocument::recipeLoaded, this,
            [this]() { showRecipe(QString::fromStdString(m_document->recipe().name)); });
    refresh();
}

void VersionsDock::setDatabase(db::Database* database) {
    m_db = database;
    refresh();
}

void VersionsDock::showRecipe(const QString& name) {
    if (name != m_name) {
        m_diff.clear();
        m_diff_table->setRowCount(0);
        m_diff_title->setText(tr("Select two versions and press Compare"));
    }
    m_name = name;
    refresh();
}

void VersionsDock::refresh() {
    m_history.clear();
    if (m_db != nullptr && !m_name.isEmpty()) {
        try {
            m_history = db::recipeHistory(*m_db, m_name.toStdString());
        } catch (const std::exception&) {
            // No version of it yet (a recipe opened from a file): an empty history.
        }
    }
    if (m_name.isEmpty()) {
        m_title->setText(tr("No recipe open"));
    } else if (m_history.empty()) {
        m_title->setText(tr("<b>%1</b>: not saved in the database yet").arg(m_name.toHtmlEscaped()));
    } else {
        m_title->setText(tr("<b>%1</b>: %n version(s)", nullptr, static_cast<int>(m_history.size()))
                             .arg(m_name.toHtmlEscaped()));
    }
    m_table->setRowCount(static_cast<int>(m_history.size()));
    for (int r = 0; r < m_table->rowCount(); ++r) {
        const db::RecipeVersionInfo& v = m_history[static_cast<std::size_t>(r)];
        const QStringList cells = {QString::number(v.version), qs(v.author), qs(v.created_at), qs(v.note)};
        for (int c = 0; c < cells.size(); ++c) {
            auto* item = new QTableWidgetItem(cells[c]);
            item->setToolTip(tr("SHA-256 %1").arg(qs(v.checksum_sha256)));
            if (v.version == m_document->version() && qs(v.recipe_name) == m_name) {
                QFont bold = item->font();
                bold.setBold(true);
                item->setFont(bold);
            }
            m_table->setItem(r, c, item);
        }
    }
    m_table->resizeColumnsToContents();
    updateButtons();
}

std::vector<int> VersionsDock::selectedVersions() const {
    std::vector<int> out;
    for (const QModelIndex& index : m_table->selectionModel()->selectedRows())
        if (index.row() < static_cast<int>(m_history.size()))
            out.push_back(m_history[static_cast<std::size_t>(index.row())].version);
    std::sort(out.begin(), out.end());
    return out;
}

void VersionsDock::updateButtons() {
    const std::size_t selected = selectedVersions().size();
    m_save->setEnabled(m_db != nullptr && m_document->hasRecipe());
    m_compare->setEnabled(selected == 2 || (selected == 1 && selectedVersions().front() > 1));
    m_open->setEnabled(selected == 1);
    m_revert->setEnabled(selected == 1);
    m_compare_render->setEnabled(selected == 1);
}

void VersionsDock::saveNewVersion(const QString& note) {
    emit saveRequested(note);
    refresh();
}

void VersionsDock::askNoteAndSave() {
    auto* dialog = new QInputDialog(this);
    dialog->setObjectName("version_note_dialog");
    dialog->setWindowTitle(tr("Save version"));
    dialog->setLabelText(tr("What changed and why:"));
    dialog->setAttribute(Qt::WA_DeleteOnClose);
    connect(dialog, &QInputDialog::textValueSelected, this, &VersionsDock::saveNewVersion);
    dialog->open();  // not exec(): the GUI thread never waits in a nested event loop
}

bool VersionsDock::diffVersions(int a, int b) {
    if (m_db == nullptr) return false;
    try {
        const std::string name = m_name.toStdString();
        const db::StoredRecipeVersion before = db::loadRecipeVersion(*m_db, name, a);
        const db::StoredRecipeVersion after = db::loadRecipeVersion(*m_db, name, b);
        m_diff = diffRecipes(before.recipe, after.recipe);
    } catch (const std::exception& e) {
        showError(tr("Cannot compare the versions"), QString::fromUtf8(e.what()));
        return false;
    }
    m_diff_title->setText(m_diff.empty() ? tr("Version %1 and version %2 are identical").arg(a).arg(b)
                                         : tr("%n change(s) from version %1 to version %2", nullptr,
                                              static_cast<int>(m_diff.size()))
                                               .arg(a)
                                               .arg(b));
    m_diff_table->setHorizontalHeaderLabels(
        {tr("Parameter"), tr("Version %1").arg(a), tr("Version %1").arg(b)});
    m_diff_table->setRowCount(static_cast<int>(m_diff.size()));
    for (int r = 0; r < m_diff_table->rowCount(); ++r) {
        const RecipeChange& c = m_diff[static_cast<std::size_t>(r)];
        const QStringList cells = {qs(c.path), qs(c.old_value), qs(c.new_value)};
        for (int col = 0; col < cells.size(); ++col) {
            auto* item = new QTableWidgetItem(cells[col]);
            item->setToolTip(cells[col]);
            m_diff_table->setItem(r, col, item);
        }
    }
    m_diff_table->resizeColumnsToContents();
    return true;
}

void VersionsDock::diffSelected() {
    const std::vector<int> v = selectedVersions();
    if (v.size() == 2) {
        diffVersions(v[0], v[1]);
    } else if (v.size() == 1 && v[0] > 1) {
        diffVersions(v[0] - 1, v[0]);
    }
}

std::optional<int> VersionsDock::revertTo(int version) {
    if (m_db == nullptr) return std::nullopt;
    try {
        const std::optional<QString> author = authorForSave(this);
        if (!author) return std::nullopt;  // no author given: nothing saved
        const db::StoredRecipeVersion old = db::loadRecipeVersion(*m_db, m_name.toStdString(), version);
        db::SaveOptions options;
        options.author = author->toStdString();
        options.note = tr("Revert to version %1").arg(version).toStdString();
        options.source = tr("%1, version %2").arg(m_name).arg(version).toStdString();
        const db::SavedVersion saved = db::saveRecipeVersion(*m_db, old.recipe, options);
        refresh();
        emit versionCreated(m_name, saved.version);
        return saved.version;
    } catch (const std::exception& e) {
        showError(tr("Cannot revert"), QString::fromUtf8(e.what()));
        return std::nullopt;
    }
}

void VersionsDock::revertSelected() {
    const std::vector<int> v = selectedVersions();
    if (v.size() != 1) return;
    const int version = v.front();
    // The revert opens the new version in the editor: unsaved edits are asked about first.
    if (mayLeave(tr("reverting to version %1").arg(version))) revertTo(version);
}

bool VersionsDock::openVersion(int version) {
    if (m_db == nullptr) return false;
    try {
        const db::StoredRecipeVersion stored = db::loadRecipeVersion(*m_db, m_name.toStdString(), version);
        m_document->load(stored.recipe, tr("%1, version %2").arg(m_name).arg(version), version);
        return true;
    } catch (const std::exception& e) {
        showError(tr("Cannot open the version"), QString::fromUtf8(e.what()));
        return false;
    }
}

bool VersionsDock::compareInRender(int version) {
    if (m_db == nullptr) return false;
    try {
        const db::StoredRecipeVersion stored = db::loadRecipeVersion(*m_db, m_name.toStdString(), version);
        emit comparisonRequested(stored.recipe, tr("%1, version %2").arg(m_name).arg(version));
        return true;
    } catch (const std::exception& e) {
        showError(tr("Cannot compare with the version"), QString::fromUtf8(e.what()));
        return false;
    }
}

void VersionsDock::showError(const QString& title, const QString& message) {
    auto* box = new QMessageBox(QMessageBox::Warning, title, message, QMessageBox::Ok, this);
    box->setObjectName("versions_error");
    box->setAttribute(Qt::WA_DeleteOnClose);
    box->open();
}

}  // namespace paintlab::gui
