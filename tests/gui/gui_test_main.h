#pragma once
// main() of the GUI tests that show VTK plots: the application's surface
// format (VTK needs an OpenGL 3.2 core profile), an application of its own
// names (so QSettings never touch a user's), then the QtTest object.

#include <QApplication>
#include <QSurfaceFormat>
#include <QTest>

namespace paintlab::test {

// Every wait of the GUI tests: ASan + llvmpipe on a loaded 2-core machine.
inline constexpr int kGuiWaitMs = 120000;

template <class Test, class Application = QApplication>
int runGuiTest(int argc, char** argv, const char* application_name) {
    QSurfaceFormat format;
    format.setVersion(3, 2);
    format.setProfile(QSurfaceFormat::CoreProfile);
    QSurfaceFormat::setDefaultFormat(format);
    Application app(argc, argv);
    QApplication::setOrganizationName("PaintLab-test");
    QApplication::setApplicationName(application_name);
    Test test;
    return QTest::qExec(&test, argc, argv);
}

}  // namespace paintlab::test
