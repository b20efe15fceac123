#include "workstation_paths.h"

#include <QCoreApplication>
#include <QCryptographicHash>
#include <QDir>
#include <QFile>
#include <QStandardPaths>

namespace paintlab::gui {

namespace {

// The demo data folder (recipes/, scenes/, ...).
std::filesystem::path demoDataDir() {
    // Installed (bin/paintlab beside share/paintlab, cmake/PaintLabPackaging.cmake):
    // the data next to the program, so that a package or a copied install
    // tree needs no environment variable. Otherwise (the build tree) the sources'.
    std::filesystem::path installed =
        std::filesystem::path(QCoreApplication::applicationDirPath().toStdString()).parent_path() / "share" /
        "paintlab";
    std::error_code error;
    if (std::filesystem::is_directory(installed / "scenes", error)) return installed;
    return {PAINTLAB_DEMO_DIR};
}

}  // namespace

std::filesystem::path demoScenePath() { return demoDataDir() / "scenes" / "car_body_sky.json"; }

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
