#pragma once
// The relit scene: the latest image the render scheduler delivered, with the
// exposure control, what it cost, and saving the image.

#include "render_scheduler.h"

#include <QDockWidget>
#include <QImage>

class QDoubleSpinBox;
class QLabel;

namespace paintlab::gui {

class RenderDock : public QDockWidget {
    Q_OBJECT
public:
    explicit RenderDock(QWidget* parent = nullptr);

    void showResult(const RenderResult& result);
    void showMessage(const QString& text);
    const QImage& image() const { return m_image; }
    double exposureEv() const;

signals:
    void exposureChanged(double exposure_ev);
    void saveImageRequested();

protected:
    void resizeEvent(QResizeEvent* event) override;

private:
    void updatePixmap();
    QLabel* m_view = nullptr;
    QLabel* m_status = nullptr;
    QDoubleSpinBox* m_exposure = nullptr;
    QImage m_image;
};

}  // namespace paintlab::gui
