#pragma once
// The ingredient browser's list as a model: a search result (name, kind,
// density; the tags as tooltip, the id as Qt::UserRole) replaced whole. A
// view asks only for the rows it shows, so listing thousands of ingredients
// costs the GUI thread next to nothing (a QTreeWidget item each took ~20 µs).

#include "paintlab/database/ingredients.h"

#include <QAbstractTableModel>

#include <optional>
#include <vector>

namespace paintlab::gui {

class IngredientListModel : public QAbstractTableModel {
public:
    using QAbstractTableModel::QAbstractTableModel;

    void setIngredients(std::vector<db::IngredientSummary> ingredients);
    const std::vector<db::IngredientSummary>& ingredients() const { return m_rows; }
    // The row of the ingredient with this id, if listed.
    std::optional<int> rowOf(std::int64_t id) const;

    int rowCount(const QModelIndex& parent = {}) const override;
    int columnCount(const QModelIndex& parent = {}) const override;
    QVariant data(const QModelIndex& index, int role = Qt::DisplayRole) const override;
    QVariant headerData(int section, Qt::Orientation orientation, int role = Qt::DisplayRole) const override;

private:
    std::vector<db::IngredientSummary> m_rows;
};

}  // namespace paintlab::gui
