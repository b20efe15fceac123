#pragma once
// What the workstation's GUI tests share: the user's folders isolated (a
// test never reads or writes the user's settings, drafts or cache), the demo
// car scene made tiny (64 x 36 pixels, so that tracing and relighting take
// well under a second even under ASan), and the measured times masked in the
// labels before a screenshot is compared with its baseline (they are the one
// thing that differs from run to run, and by 4x under the sanitizers).
// The workstation tests open their window through openWorkstation.

#include "author_setting.h"
#include "main_window.h"

#include <QDir>
#include <QLabel>
#include <QRegularExpression>
#include <QSize>
#include <QString>
#include <QTest>
#include <QWidget>
#include <QtGlobal>

#include <nlohmann/json.hpp>

#include <fstream>
#include <memory>

namespace paintlab::test {

// XDG_CACHE_HOME (ray maps, fonts, shaders), XDG_CONFIG_HOME (QSettings: the
// layout, recent files, the author) and XDG_DATA_HOME (recovery drafts) in
// <root>/cache, /config and /data. Call before the first window or QSettings.
inline void isolateUserFolders(const QString& root) {
    qputenv("XDG_CACHE_HOME", (root + "/cache").toUtf8());
    qputenv("XDG_CONFIG_HOME", (root + "/config").toUtf8());
    qputenv("XDG_DATA_HOME", (root + "/data").toUtf8());
}

// The tests' user: folders isolated under `root` and an author remembered,
// so the first save asks no question.
inline void prepareTestUser(const QString& root) {
    isolateUserFolders(root);
    gui::rememberAuthor(QStringLiteral("GUI test"));
}

// Options for a workstation on `database` (created from the demo data when
// new) that opens no scene: the cases that need no render start fast.
inline gui::WorkstationOptions withoutScene(const QString& database) {
    gui::WorkstationOptions options;
    options.database = database.toStdString();
    options.open_scene = false;
    return options;
}

// The main window with `options`, resized to `size` unless empty, shown;
// nullptr when the window system never exposed it.
inline std::unique_ptr<gui::MainWindow> openWorkstation(const gui::WorkstationOptions& options,
                                                        QSize size = {}) {
    auto window = std::make_unique<gui::MainWindow>(options);
    if (!size.isEmpty()) window->resize(size);
    window->show();
    if (!QTest::qWaitForWindowExposed(window.get())) return nullptr;
    return window;
}

// Writes the demo scene at 64 x 36 pixels into <folder>/scenes/car.json; returns its path.
inline QString writeTinyDemoScene(const QString& folder) {
    std::ifstream in(std::string(PAINTLAB_DEMO_DIR) + "/scenes/car_body_sky.json");
    nlohmann::json scene = nlohmann::json::parse(in);
    scene["camera"]["width"] = 64;
    scene["camera"]["height"] = 36;
    QDir().mkpath(folder + "/scenes");
    QString file = folder + "/scenes/car.json";
    std::ofstream(file.toStdString()) << scene.dump(2);
    return file;
}

// "12.3 ms" becomes "#.# ms" in every label under `root`.
inline void maskMeasuredTimes(QWidget& root) {
    static const QRegularExpression time(QStringLiteral("[0-9]+\\.[0-9] ms"));
    for (QLabel* label : root.findChildren<QLabel*>())
        if (label->text().contains(time))
            label->setText(label->text().replace(time, QStringLiteral("#.# ms")));
}

}  // namespace paintlab::test
