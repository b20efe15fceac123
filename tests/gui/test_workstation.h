#pragma once
// The workstation test's fixture (test_workstation.cpp): one main window on
// a demo database and a small demo scene, shared by every case; the version
// comparison cases are in test_workstation_compare.cpp.

#include "gui_test_main.h"
#include "main_window.h"
#include "render_scheduler.h"

#include "paintlab/engine/fast_model/layered_brdf.h"
#include "paintlab/engine/recipe.h"

#include <QObject>
#include <QString>
#include <QTemporaryDir>

#include <memory>

namespace paintlab::test {

inline constexpr int kWaitMs = kGuiWaitMs;
inline const QString kPearl = QStringLiteral("Blue pearl over black (two layers)");

}  // namespace paintlab::test

class WorkstationTest : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void startsOnTheDemoDatabase();
    void pearlescentShowsPlotAndImage();
    void screenshotsMatchBaselines();
    void sliderChangesPlotAndRenderAndUndoRestoresExactly();
    void savingCreatesANewVersion();
    void malformedRecipeFileGivesAnErrorDialog();
    void rapidEditsEndOnTheFinalRecipe();
    void draggingNeverFreezesTheGuiThread();
    void accuracyDockListsThePlanWithReasons();
    void turningThePlanOffChangesWhatIsComputed();
    void previewsLeaveTheGlintsForTheRelease();
    void splitViewHalvesEqualTheSingleRenders();
    void sideBySideShowsBoth();
    void switchingVersionsRendersTheOtherVersion();
    void cleanupTestCase();

private:
    void waitIdle();
    void waitComparison();
    // A fresh render of `recipe` on a scheduler of its own, with the window's
    // ray map, exposure and plan setting at `preset`.
    paintlab::gui::RenderResult singleRender(const paintlab::Recipe& recipe, paintlab::Preset preset);
    // The recipe's latest render by the window's scheduler (a new request).
    paintlab::gui::RenderResult renderNow();
    QTemporaryDir m_dir;
    std::unique_ptr<paintlab::gui::MainWindow> m_window;
};
