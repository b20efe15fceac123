#pragma once
// The relit scene, the main window's central widget (window_layout.h): the
// latest image scaled to the room it has (aspect kept), the latest image the render scheduler delivered, with
// the exposure control, what it cost, and saving the image; and the comparison of the edited recipe with
// another version (picked in the Versions dock, or the current recipe pinned): single, side by side, or split
// by a draggable vertical divider (left: the edited recipe, right: the comparison), each side labelled with
// its version. Both sides come from renders of the same ray map at the same settings (the main window asks
// both schedulers), so the composition is pixel for pixel what each recipe gives (comparison_image.h).

#include "comparison_image.h"
#include "render_scheduler.h"

#include <QImage>
#include <QWidget>

class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QPushButton;

namespace paintlab::gui {

class ComparisonView;

class RenderDock : public QWidget {
    Q_OBJECT
public:
    explicit RenderDock(QWidget* parent = nullptr);

    void showResult(const RenderResult& result);
    void showMessage(const QString& text);
    // The edited recipe's latest image (single view).
    const QImage& image() const { return m_image; }
    double exposureEv() const;
    // The picture's room in device pixels (what a ray map traced for it should fill).
    QSize viewPixels() const;

    // The label of the edited recipe's side ("current: <origin>").
    void setCurrentLabel(const QString& label);
    // The comparison's render (its label set by setComparisonLabel first).
    void setComparisonLabel(const QString& label);
    void showComparison(const RenderResult& result);
    void clearComparison();
    bool hasComparison() const { return !m_comparison_label.isEmpty(); }
    const QImage& comparisonImage() const { return m_comparison; }
    const QString& comparisonLabel() const { return m_comparison_label; }

    CompareMode mode() const;
    void setMode(CompareMode mode);
    // The split divider at this fraction of the width (0..1).
    void setSplitFraction(double fraction);
    double splitFraction() const { return m_split; }
    // The composed pixels as shown (single: image()), without captions.
    QImage shownPixels() const;
    // What "Save image" writes: the single image as it is; a comparison with
    // its captions above (captionedImage).
    QImage imageToSave() const;

signals:
    void exposureChanged(double exposure_ev);
    void saveImageRequested();
    void pinCurrentRequested();
    void clearComparisonRequested();

private:
    void updateView();
    ComparisonView* m_view = nullptr;
    QComboBox* m_mode = nullptr;
    QPushButton* m_pin = nullptr;
    QPushButton* m_clear = nullptr;
    QLabel* m_status = nullptr;
    QLabel* m_comparison_status = nullptr;
    QDoubleSpinBox* m_exposure = nullptr;
    QImage m_image;
    QImage m_comparison;
    QString m_current_label;
    QString m_comparison_label;
    double m_split = 0.5;
};

}  // namespace paintlab::gui
