#include "workstation_paths.h"

#include <QCryptographicHash>
#include <QDir>
#include <QFile>
#include <QStandardPaths>

namespace paintlab::gui {

std::filesystem::path demoScenePath() {
    return std::filesystem::path(PAINTLAB_DEMO_DIR) / "scenes" / "car_body_sky.json";
}

std::filesystem::path cachedRayMapPath(const std::filesystem::path& scene, const QString& variant) {
    QFile file(QString::fromStdString(scene.string()));
    QCryptographicHash hash(QCryptographicHash::Sha256);
    if (file.open(QIODevice::ReadOnly)) hash.addData(&file);
    const QString tag = QString::fromLatin1(hash.result().toHex().left(12));
    const QString folder = QStandardPaths::writableLocation(QStandardPaths::CacheLocation) + "/raymaps";
    QDir().mkpath(folder);
    const QString name = QString::fromStdString(scene.stem().string()) + "-" + tag + variant + ".prm";
    return {(folder + "/" + name).toStdString()};
}

}  // namespace paintlab::gui
