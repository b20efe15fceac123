#include "ingredient_dock.h"

#include "format_dialog.h"

#include "ingredient_list_model.h"
#include "recipe_ingredient.h"
#include "replace_recipe_command.h"
#include "spectrum_chart.h"

#include "paintlab/database/exchange.h"
#include "paintlab/engine/error.h"
#include "paintlab/engine/io/atomic_file.h"
#include "paintlab/plugins/exchange.h"

#include <QComboBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QMessageBox>
#include <QPlainTextEdit>
#include <QPushButton>
#include <QScrollArea>
#include <QSignalBlocker>
#include <QSplitter>
#include <QTableWidget>
#include <QTimer>
#include <QTreeView>
#include <QUndoStack>
#include <QVBoxLayout>

#include <exception>
#include <utility>

namespace paintlab::gui {

namespace {

constexpr int kIdRole = Qt::UserRole;
constexpr int kKinds = 5;  // IngredientKind's values
const char* const kSource = "ingredient editor";

QString qs(const std::string& s) { return QString::fromStdString(s); }

QString fieldLabel(const IngredientField& field) {
    return field.unit.empty() ? qs(field.label) : qs(field.label) + " (" + qs(field.unit) + ")";
}

QString editorText(const QWidget* editor) {
    if (const auto* line = qobject_cast<const QLineEdit*>(editor)) return line->text();
    if (const auto* text = qobject_cast<const QPlainTextEdit*>(editor)) return text->toPlainText();
    return {};
}

}  // namespace

IngredientDock::IngredientDock(RecipeDocument* document, QWidget* parent)
    : QDockWidget(tr("Ingredients"), parent), m_document(document) {
    setObjectName("ingredients");
    auto* body = new QWidget(this);
    auto* layout = new QVBoxLayout(body);

    auto* filters = new QHBoxLayout;
    m_search = new QLineEdit(body);
    m_search->setObjectName("ingredient_search");
    m_search->setPlaceholderText(tr("Search by name"));
    m_search->setClearButtonEnabled(true);
    m_kind = new QComboBox(body);
    m_kind->setObjectName("ingredient_kind_filter");
    m_kind->addItem(tr("All kinds"), -1);
    for (int k = 0; k < kKinds; ++k)
        m_kind->addItem(qs(ingredientKindLabel(static_cast<db::IngredientKind>(k))), k);
    // As narrow as ten characters (the longest kind is elided): the dock fits a 360-pixel column.
    m_kind->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
    m_kind->setMinimumContentsLength(10);
    filters->addWidget(m_search, 1);
    filters->addWidget(m_kind);
    layout->addLayout(filters);

    auto* split = new QSplitter(Qt::Vertical, body);
    split->setObjectName("ingredient_split");
    m_list = new QTreeView(split);
    m_list->setObjectName("ingredient_list");
    m_list->setRootIsDecorated(false);
    m_list->setUniformRowHeights(true);
    m_list->setSelectionMode(QAbstractItemView::SingleSelection);
    m_model = new IngredientListModel(this);
    m_list->setModel(m_model);
    m_list->header()->setSectionResizeMode(0, QHeaderView::Stretch);
    m_list->header()->setStretchLastSection(false);
    split->addWidget(m_list);

    auto* scroll = new QScrollArea(split);
    scroll->setWidgetResizable(true);
    auto* details = new QWidget(scroll);
    auto* details_layout = new QVBoxLayout(details);
    m_header = new QLabel(tr("No ingredient selected"), details);
    m_header->setObjectName("ingredient_header");
    m_header->setWordWrap(true);
    m_header->setTextInteractionFlags(Qt::TextSelectableByMouse);
    details_layout->addWidget(m_header);
    m_form_host = new QWidget(details);
    m_form = new QFormLayout(m_form_host);
    m_form->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);
    details_layout->addWidget(m_form_host);
    details_layout->addStretch(1);
    scroll->setWidget(details);
    split->addWidget(scroll);

    // The spectra in a pane of their own, so the preview stays in view.
    auto* spectra_box = new QWidget(split);
    auto* spectra_layout = new QVBoxLayout(spectra_box);
    spectra_layout->setContentsMargins(0, 0, 0, 0);
    m_spectra = new QTableWidget(0, 5, spectra_box);
    m_spectra->setObjectName("ingredient_spectra");
    m_spectra->setHorizontalHeaderLabels(
        {tr("Spectrum"), tr("Unit"), tr("Samples"), tr("Source"), tr("Date")});
    m_spectra->setSelectionBehavior(QAbstractItemView::SelectRows);
    m_spectra->setSelectionMode(QAbstractItemView::SingleSelection);
    m_spectra->setEditTriggers(QAbstractItemView::NoEditTriggers);
    m_spectra->verticalHeader()->hide();
    m_spectra->horizontalHeader()->setStretchLastSection(true);
    m_spectra->setMaximumHeight(100);
    spectra_layout->addWidget(m_spectra);
    m_chart = new SpectrumChart(spectra_box);
    spectra_layout->addWidget(m_chart, 1);
    split->addWidget(spectra_box);
    split->setSizes({250, 170, 250});  // in proportion: the list and the spectra first, the fields scroll
    layout->addWidget(split, 1);

    // Three short rows, so the dock fits a 360-pixel column: adding to the
    // recipe, editing the ingredient, files and the status.
    auto* add_row = new QHBoxLayout;
    m_add = new QPushButton(tr("Add to layer"), body);
    m_add->setObjectName("ingredient_add");
    m_add->setToolTip(tr("Add the selected ingredient to a layer of the recipe being edited (undoable)"));
    m_layer = new QComboBox(body);
    m_layer->setObjectName("ingredient_layer");
    add_row->addWidget(m_add);
    add_row->addWidget(m_layer, 1);
    layout->addLayout(add_row);

    auto* edit_row = new QHBoxLayout;
    m_save = new QPushButton(tr("Save changes"), body);
    m_save->setObjectName("ingredient_save");
    m_revert = new QPushButton(tr("Revert"), body);
    edit_row->addWidget(m_save);
    edit_row->addWidget(m_revert);
    edit_row->addStretch(1);
    layout->addLayout(edit_row);

    auto* file_row = new QHBoxLayout;
    m_import = new QPushButton(tr("Import..."), body);
    m_import->setToolTip(tr("Import an ingredient file (JSON or CSV): all of it or, on an error, nothing"));
    m_export = new QPushButton(tr("Export..."), body);
    m_export->setToolTip(tr("Export the listed ingredients as JSON or CSV"));
    m_status = new QLabel(body);
    m_status->setObjectName("ingredient_status");
    m_status->setWordWrap(true);
    file_row->addWidget(m_import);
    file_row->addWidget(m_export);
    file_row->addWidget(m_status, 1);
    layout->addLayout(file_row);
    setWidget(body);

    m_search_delay = new QTimer(this);
    m_search_delay->setObjectName("search_delay");
    m_search_delay->setSingleShot(true);
    m_search_delay->setInterval(150);  // typing does not query on every key
    connect(m_search_delay, &QTimer::timeout, this, &IngredientDock::refresh);
    connect(m_search, &QLineEdit::textChanged, m_search_delay, qOverload<>(&QTimer::start));
    connect(m_kind, &QComboBox::currentIndexChanged, this, &IngredientDock::refresh);
    connect(m_list->selectionModel(), &QItemSelectionModel::currentRowChanged, this,
            [this](const QModelIndex& current) {
                if (m_filling) return;
                showIngredient(current.isValid()
                                   ? std::optional<std::int64_t>(current.data(kIdRole).toLongLong())
                                   : std::nullopt);
            });
    connect(m_spectra, &QTableWidget::currentCellChanged, this, [this](int row) { showSpectrum(row); });
    connect(m_save, &QPushButton::clicked, this, &IngredientDock::saveChanges);
    connect(m_revert, &QPushButton::clicked, this, &IngredientDock::revertChanges);
    connect(m_add, &QPushButton::clicked, this, [this]() { addToLayer(m_layer->currentData().toInt()); });
    connect(m_import, &QPushButton::clicked, this, &IngredientDock::browseImport);
    connect(m_export, &QPushButton::clicked, this, &IngredientDock::browseExport);
    connect(&m_worker, &DatabaseWorker::busyChanged, this, &IngredientDock::updateButtons);
    connect(document, &RecipeDocument::recipeChanged, this, &IngredientDock::fillLayers);
    // One selected layer, shared with the recipe editor's layer list: "Add to
    // layer" adds to the layer selected there, and a layer chosen here is selected there.
    connect(document, &RecipeDocument::selectedLayerChanged, this, [this](int layer) {
        if (layer >= 0 && layer < m_layer->count()) m_layer->setCurrentIndex(layer);
    });
    connect(m_layer, &QComboBox::activated, m_document, &RecipeDocument::setSelectedLayer);
    fillLayers();
    updateButtons();
}

void IngredientDock::setDatabase(db::Database* database) {
    m_db = database;
    m_worker.setFile(database != nullptr ? database->file() : std::filesystem::path());
    m_reader.setFile(m_worker.file());
    refresh();
}

void IngredientDock::refresh() {
    m_search_delay->stop();
    if (m_db == nullptr) {
        showList({});
        return;
    }
    // One search at a time; a request made meanwhile runs when it ends, with
    // the filter as it is then (the stale result is not shown).
    if (m_search_running) {
        m_search_pending = true;
        return;
    }
    db::IngredientFilter filter;
    filter.name_contains = m_search->text().trimmed().toStdString();
    if (const int kind = m_kind->currentData().toInt(); kind >= 0)
        filter.kind = static_cast<db::IngredientKind>(kind);
    m_search_running = true;
    m_reader.run<std::vector<db::IngredientSummary>>(
        [filter](db::Database& db) { return db::searchIngredients(db, filter); },
        [this](std::vector<db::IngredientSummary> found) {
            m_search_running = false;
            if (m_search_pending) {
                m_search_pending = false;
                refresh();
                return;
            }
            showList(std::move(found));
        },
        [this](const QString& message) {
            m_search_running = false;
            m_search_pending = false;
            showList({});
            showError(tr("Cannot list the ingredients"), message);
        });
}

bool IngredientDock::searching() const { return m_search_running || m_search_delay->isActive(); }

void IngredientDock::showList(std::vector<db::IngredientSummary> found) {
    const std::optional<std::int64_t> keep =
        m_current ? std::optional(m_current->id) : std::optional<std::int64_t>();
    std::optional<int> reselect;
    {
        // The model is replaced whole; the view asks for the rows it shows.
        m_filling = true;
        m_model->setIngredients(std::move(found));
        if (keep) reselect = m_model->rowOf(*keep);
        if (reselect) m_list->setCurrentIndex(m_model->index(*reselect, 0));
        m_filling = false;
    }
    const int count = m_model->rowCount();
    m_status->setText(tr("%n ingredient(s) listed", nullptr, count));
    // The selection survives when the ingredient is still listed: its fields
    // are read again, unless they hold edits not saved yet.
    if (!reselect || !m_modified) showIngredient(reselect ? keep : std::nullopt);
    updateButtons();
    emit listed(count);
}

const std::vector<db::IngredientSummary>& IngredientDock::listedIngredients() const {
    return m_model->ingredients();
}

bool IngredientDock::selectIngredient(db::IngredientKind kind, const QString& name) {
    const std::string wanted = name.toStdString();
    const auto& rows = m_model->ingredients();
    for (std::size_t i = 0; i < rows.size(); ++i) {
        if (rows[i].kind == kind && rows[i].name == wanted) {
            m_list->setCurrentIndex(m_model->index(static_cast<int>(i), 0));
            return true;
        }
    }
    return false;
}

void IngredientDock::showIngredient(std::optional<std::int64_t> id) {
    m_current.reset();
    m_current_spectra.clear();
    if (id && m_db != nullptr) {
        try {
            m_current = db::readIngredient(*m_db, *id);
            m_current_spectra = db::ingredientSpectra(*m_db, *id);
        } catch (const std::exception& e) {
            m_current.reset();
            showError(tr("Cannot read the ingredient"), QString::fromUtf8(e.what()));
        }
    }
    if (m_current) {
        const db::Ingredient& ing = *m_current;
        m_header->setText(tr("<b>%1</b> &nbsp;%2, id %3")
                              .arg(qs(ing.name).toHtmlEscaped(), qs(ingredientKindLabel(ing.kind())))
                              .arg(ing.id));
    } else {
        m_header->setText(tr("No ingredient selected"));
    }
    buildForm();
    {
        const QSignalBlocker block(m_spectra);
        m_spectra->setRowCount(static_cast<int>(m_current_spectra.size()));
        for (int r = 0; r < m_spectra->rowCount(); ++r) {
            const db::StoredSpectrum& s = m_current_spectra[static_cast<std::size_t>(r)];
            const std::size_t n = s.spectrum.values().size();
            const QStringList cells = {qs(s.quantity), qs(s.info.unit),
                                       n == 1 ? tr("constant %1").arg(s.spectrum.values().front())
                                              : tr("%1, %2-%3 nm")
                                                    .arg(n)
                                                    .arg(s.spectrum.wavelengthsNm().front())
                                                    .arg(s.spectrum.wavelengthsNm().back()),
                                       qs(s.info.source), qs(s.info.date)};
            for (int c = 0; c < cells.size(); ++c) {
                auto* cell = new QTableWidgetItem(cells[c]);
                cell->setToolTip(cells[c]);
                m_spectra->setItem(r, c, cell);
            }
        }
        m_spectra->resizeColumnsToContents();
        if (m_spectra->rowCount() > 0) m_spectra->setCurrentCell(0, 0);
    }
    showSpectrum(m_spectra->rowCount() > 0 ? 0 : -1);
    setModified(false);
}

void IngredientDock::buildForm() {
    while (m_form->rowCount() > 0) m_form->removeRow(0);
    m_editors.clear();
    m_fields.clear();
    if (!m_current) return;
    m_fields = ingredientFields(*m_current);
    for (const IngredientField& field : m_fields) {
        QWidget* editor = nullptr;
        const QString text = qs(fieldText(*m_current, field));
        if (field.type == IngredientField::Type::LongText) {
            auto* edit = new QPlainTextEdit(text, m_form_host);
            edit->setMaximumHeight(56);
            connect(edit, &QPlainTextEdit::textChanged, this, [this]() { setModified(true); });
            editor = edit;
        } else {
            auto* edit = new QLineEdit(text, m_form_host);
            if (field.type == IngredientField::Type::OptionalNumber)
                edit->setPlaceholderText(tr("not given"));
            edit->setCursorPosition(0);
            connect(edit, &QLineEdit::textEdited, this, [this]() { setModified(true); });
            editor = edit;
        }
        editor->setObjectName(qs(field.key));
        editor->setToolTip(qs(field.help));
        auto* label = new QLabel(fieldLabel(field), m_form_host);
        label->setToolTip(qs(field.help));
        m_form->addRow(label, editor);
        m_editors[field.key] = editor;
    }
    // What the ingredient's kind carries that is not edited here.
    if (m_current->kind() == db::IngredientKind::Substrate) {
        const auto& substrate = std::get<Substrate>(m_current->data);
        const std::string_view kind = substrateKind(substrate);
        m_form->insertRow(
            0, tr("Substrate kind"),
            new QLabel(QString::fromUtf8(kind.data(), static_cast<int>(kind.size())), m_form_host));
    }
}

void IngredientDock::showSpectrum(int row) {
    if (row < 0 || row >= static_cast<int>(m_current_spectra.size())) {
        m_chart->clear();
        return;
    }
    const db::StoredSpectrum& s = m_current_spectra[static_cast<std::size_t>(row)];
    m_chart->setSpectrum(qs(s.quantity), qs(s.info.unit), s.spectrum.wavelengthsNm(), s.spectrum.values());
}

QWidget* IngredientDock::fieldEditor(const std::string& key) const {
    const auto it = m_editors.find(key);
    return it == m_editors.end() ? nullptr : it->second;
}

void IngredientDock::markField(const std::string& key) {
    for (auto& [k, editor] : m_editors) editor->setStyleSheet(k == key ? "border: 2px solid #d62728;" : "");
    if (QWidget* editor = fieldEditor(key)) editor->setFocus();
}

bool IngredientDock::saveChanges() {
    if (!m_current || m_db == nullptr) return false;
    db::Ingredient edited = *m_current;
    for (const IngredientField& field : m_fields) {
        try {
            setFieldText(edited, field, editorText(fieldEditor(field.key)).toStdString(), kSource);
        } catch (const InputError& e) {
            markField(field.key);
            showError(tr("Cannot save the ingredient"),
                      tr("%1: %2").arg(fieldLabel(field), QString::fromUtf8(e.what())));
            return false;
        }
    }
    try {
        // Validates every value against its range first; nothing is written on an error.
        db::updateIngredient(*m_db, edited);
    } catch (const InputError& e) {
        const std::string key = fieldKeyOfError(m_fields, e.field());
        markField(key);
        QString text = QString::fromUtf8(e.what());
        for (const IngredientField& field : m_fields)
            if (field.key == key) text = tr("%1: %2").arg(fieldLabel(field), text);
        showError(tr("Cannot save the ingredient"), text);
        return false;
    } catch (const std::exception& e) {
        showError(tr("Cannot save the ingredient"), QString::fromUtf8(e.what()));
        return false;
    }
    markField({});
    m_current = edited;  // as stored; the list is read again (its name or density may have changed)
    setModified(false);
    refresh();  // the name or density shown in the list may have changed
    m_status->setText(tr("Saved %1").arg(qs(edited.name)));
    emit ingredientsChanged();
    return true;
}

void IngredientDock::revertChanges() {
    showIngredient(m_current ? std::optional(m_current->id) : std::nullopt);
}

void IngredientDock::setModified(bool modified) {
    m_modified = modified;
    updateButtons();
}

void IngredientDock::updateButtons() {
    const bool busy = m_worker.busy();
    m_save->setEnabled(m_current.has_value() && m_modified && !busy);
    m_revert->setEnabled(m_current.has_value() && m_modified);
    m_import->setEnabled(m_db != nullptr && !busy);
    m_export->setEnabled(m_db != nullptr && !busy && m_model->rowCount() > 0);
    const bool substrate = m_current && m_current->kind() == db::IngredientKind::Substrate;
    m_add->setEnabled(m_current.has_value() && m_document->hasRecipe());
    m_add->setText(substrate ? tr("Use as substrate") : tr("Add to layer"));
    m_layer->setEnabled(!substrate && m_document->hasRecipe());
}

void IngredientDock::fillLayers() {
    const int keep = m_layer->currentIndex();
    const QSignalBlocker block(m_layer);
    m_layer->clear();
    if (m_document->hasRecipe()) {
        const Recipe& recipe = m_document->recipe();
        for (std::size_t l = 0; l < recipe.layers.size(); ++l)
            m_layer->addItem(tr("%1. %2").arg(l + 1).arg(qs(recipe.layers[l].name)), static_cast<int>(l));
    }
    const int selected = m_document->selectedLayer();
    if (selected >= 0 && selected < m_layer->count()) {
        m_layer->setCurrentIndex(selected);
    } else if (keep >= 0 && keep < m_layer->count()) {
        m_layer->setCurrentIndex(keep);
    }
    updateButtons();
}

bool IngredientDock::addToLayer(int layer) {
    if (!m_current || !m_document->hasRecipe()) return false;
    try {
        Recipe changed = withIngredient(m_document->recipe(), layer, *m_current);
        m_document->undoStack()->push(new ReplaceRecipeCommand(
            m_document, std::move(changed), qs(additionText(m_document->recipe(), layer, *m_current))));
        m_status->setText(m_document->undoStack()->undoText());
        return true;
    } catch (const std::exception& e) {
        showError(tr("Cannot add the ingredient"), QString::fromUtf8(e.what()));
        return false;
    }
}

void IngredientDock::importFile(const QString& path, const std::optional<std::string>& format_id) {
    const std::filesystem::path file = path.toStdString();
    m_status->setText(tr("Importing %1...").arg(path));
    m_worker.run<db::ImportResult>(
        [file, format_id](db::Database& db) {
            plugins::ImportRequest request;
            request.options.kind = db::ContentKind::Ingredients;
            request.format_id = format_id;
            return plugins::importFile(db, file, request);
        },
        [this, path](const db::ImportResult& result) {
            refresh();
            const QString message =
                tr("Imported %n ingredient(s) from %1", nullptr, static_cast<int>(result.names.size()))
                    .arg(path);
            m_status->setText(message);
            emit ingredientsChanged();
            emit importFinished(true, message);
        },
        [this](const QString& message) {
            m_status->setText(tr("Import failed: nothing was stored"));
            showError(tr("Cannot import the file"), message + tr("\n\nNothing of the file was stored."));
            emit importFinished(false, message);
        });
}

void IngredientDock::exportFile(const QString& path, const std::optional<std::string>& format_id) {
    std::vector<std::string> names;
    names.reserve(m_model->ingredients().size());
    for (const db::IngredientSummary& s : m_model->ingredients()) names.push_back(s.name);
    if (names.empty()) {
        const QString message = tr("No ingredient is listed: nothing to export");
        showError(tr("Cannot export"), message);
        emit exportFinished(false, message);
        return;
    }
    // The exporter as `db export` chooses it: by the format chosen, else by the extension.
    const std::filesystem::path file = path.toStdString();
    const plugins::Registry& registry = plugins::Registry::global();
    const plugins::IngredientExporter* exporter = registry.ingredientExporterFor(file, format_id);
    if (exporter == nullptr) {
        const QString message =
            tr("%1: cannot tell the format from the extension '%2': ingredients are exported as %3")
                .arg(path, QString::fromStdString(file.extension().string()),
                     QString::fromStdString(plugins::describeFormats(
                         plugins::offeredFormats(registry, plugins::OfferKind::IngredientExport))));
        showError(tr("Cannot export"), message);
        emit exportFinished(false, message);
        return;
    }
    m_status->setText(tr("Exporting to %1...").arg(path));
    m_worker.run<int>(
        [names, exporter, file](db::Database& db) {
            io::writeFileAtomically(file, exporter->text(db::ingredientsByName(db, names)));
            return static_cast<int>(names.size());
        },
        [this, path](int count) {
            const QString message = tr("Exported %n ingredient(s) to %1", nullptr, count).arg(path);
            m_status->setText(message);
            emit exportFinished(true, message);
        },
        [this](const QString& message) {
            m_status->setText(tr("Export failed"));
            showError(tr("Cannot export"), message);
            emit exportFinished(false, message);
        });
}

void IngredientDock::browseImport() {
    const auto chosen = chooseFileToOpen(
        this, QStringLiteral("ingredient_import_dialog"), tr("Import ingredients"),
        QStringLiteral("ingredients/lastFolder"),
        plugins::offeredFormats(plugins::Registry::global(), plugins::OfferKind::IngredientImport));
    if (chosen) importFile(chosen->path, chosen->format_id);
}

void IngredientDock::browseExport() {
    const auto chosen = chooseFileToSave(
        this, QStringLiteral("ingredient_export_dialog"), tr("Export the listed ingredients"),
        QStringLiteral("ingredients/lastFolder"),
        plugins::offeredFormats(plugins::Registry::global(), plugins::OfferKind::IngredientExport));
    if (chosen) exportFile(chosen->path, chosen->format_id);
}

void IngredientDock::showError(const QString& title, const QString& message) {
    m_status->setText(message.section('\n', 0, 0));
    auto* box = new QMessageBox(QMessageBox::Warning, title, message, QMessageBox::Ok, this);
    box->setObjectName("ingredient_error");
    box->setAttribute(Qt::WA_DeleteOnClose);
    box->open();  // not exec(): never blocks the GUI thread (or a test)
}

}  // namespace paintlab::gui
