#include "ingredient_list_model.h"

#include "ingredient_fields.h"

#include <QCoreApplication>
#include <QStringList>

#include <utility>

namespace paintlab::gui {

void IngredientListModel::setIngredients(std::vector<db::IngredientSummary> ingredients) {
    beginResetModel();
    m_rows = std::move(ingredients);
    endResetModel();
}

std::optional<int> IngredientListModel::rowOf(std::int64_t id) const {
    for (std::size_t i = 0; i < m_rows.size(); ++i)
        if (m_rows[i].id == id) return static_cast<int>(i);
    return std::nullopt;
}

int IngredientListModel::rowCount(const QModelIndex& parent) const {
    return parent.isValid() ? 0 : static_cast<int>(m_rows.size());
}

int IngredientListModel::columnCount(const QModelIndex& parent) const { return parent.isValid() ? 0 : 3; }

QVariant IngredientListModel::data(const QModelIndex& index, int role) const {
    if (!index.isValid() || index.row() >= static_cast<int>(m_rows.size())) return {};
    const db::IngredientSummary& s = m_rows[static_cast<std::size_t>(index.row())];
    switch (role) {
    case Qt::DisplayRole:
        if (index.column() == 0) return QString::fromStdString(s.name);
        if (index.column() == 1) return QString::fromStdString(ingredientKindLabel(s.kind));
        return s.density_g_cm3 ? QVariant(QString::number(*s.density_g_cm3)) : QVariant();
    case Qt::ToolTipRole: {
        QStringList tags;
        for (const std::string& t : s.tags) tags << QString::fromStdString(t);
        return tags.isEmpty() ? QVariant()
                              : QVariant(QCoreApplication::translate("IngredientDock", "Tags: %1")
                                             .arg(tags.join(QStringLiteral(", "))));
    }
    case Qt::UserRole:
        return QVariant::fromValue<qlonglong>(s.id);
    default:
        return {};
    }
}

QVariant IngredientListModel::headerData(int section, Qt::Orientation orientation, int role) const {
    if (orientation != Qt::Horizontal || role != Qt::DisplayRole) return {};
    switch (section) {
    case 0:
        return QCoreApplication::translate("IngredientDock", "Name");
    case 1:
        return QCoreApplication::translate("IngredientDock", "Kind");
    case 2:
        return QCoreApplication::translate("IngredientDock", "Density (g/cm³)");
    default:
        return {};
    }
}

}  // namespace paintlab::gui
