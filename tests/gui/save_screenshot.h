#pragma once
// Saves a widget's screenshot next to the test log for a person to look at
// (no baseline comparison: screenshot_baseline.h does that): into
// $PAINTLAB_SCREENSHOT_DIR, else the test's PAINTLAB_SCREENSHOT_DIR.

#include <QDir>
#include <QString>
#include <QTest>
#include <QWidget>

namespace paintlab::test {

inline void saveScreenshot(QWidget* widget, const QString& name) {
    QString dir = qEnvironmentVariable("PAINTLAB_SCREENSHOT_DIR");
    if (dir.isEmpty()) dir = QStringLiteral(PAINTLAB_SCREENSHOT_DIR);
    QDir().mkpath(dir);
    const QString file = dir + "/" + name + ".png";
    QVERIFY2(widget->grab().save(file), qPrintable(file));
}

}  // namespace paintlab::test
