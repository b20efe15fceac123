#pragma once
// What the plot tests share (test_plots.cpp, test_full_model_overlay.cpp):
// the demo recipes and the plots'
// CSV exports read back with the one CSV reader (io/csv.h).

#include "paintlab/engine/io/csv.h"
#include "paintlab/engine/recipe.h"
#include "paintlab/engine/recipe_json.h"

#include <QByteArray>
#include <QFile>
#include <QString>
#include <QStringList>

#include <string>
#include <string_view>
#include <vector>

namespace paintlab::test {

inline Recipe silverRecipe() {
    return loadRecipeFile(std::string(PAINTLAB_DEMO_DIR) + "/recipes/silver-metallic.json");
}

inline Recipe pearlRecipe() {
    return loadRecipeFile(std::string(PAINTLAB_DEMO_DIR) + "/recipes/pearlescent-two-layer.json");
}

// A CSV file as rows of cells.
struct Csv {
    QStringList header;
    std::vector<QStringList> rows;
    int column(const QString& name) const { return static_cast<int>(header.indexOf(name)); }
    double number(std::size_t row, const QString& name) const { return rows[row][column(name)].toDouble(); }
};

inline Csv readCsv(const QString& path) {
    Csv csv;
    QFile file(path);
    if (!file.open(QIODevice::ReadOnly)) return csv;
    const QByteArray bytes = file.readAll();
    const io::CsvTable table = io::CsvTable::parse(
        std::string_view(bytes.constData(), static_cast<std::size_t>(bytes.size())), path.toStdString());
    for (const std::string& name : table.header()) csv.header << QString::fromStdString(name);
    for (const io::CsvRecord& record : table.records()) {
        QStringList row;
        for (const std::string& field : record.fields) row << QString::fromStdString(field);
        csv.rows.push_back(row);
    }
    return csv;
}

}  // namespace paintlab::test
