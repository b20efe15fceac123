#include "render_dock.h"

#include <QDoubleSpinBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QVBoxLayout>

namespace paintlab::gui {

RenderDock::RenderDock(QWidget* parent) : QDockWidget(tr("Render"), parent) {
    setObjectName("render");
    auto* body = new QWidget(this);
    auto* layout = new QVBoxLayout(body);
    m_view = new QLabel(tr("No image yet"), body);
    m_view->setAlignment(Qt::AlignCenter);
    m_view->setMinimumSize(240, 135);
    m_view->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Ignored);
    layout->addWidget(m_view, 1);
    auto* controls = new QHBoxLayout();
    controls->addWidget(new QLabel(tr("Exposure"), body));
    m_exposure = new QDoubleSpinBox(body);
    m_exposure->setRange(-8.0, 8.0);
    m_exposure->setSingleStep(0.25);
    m_exposure->setSuffix(" EV");
    m_exposure->setObjectName("exposure");
    controls->addWidget(m_exposure);
    auto* save = new QPushButton(tr("Save image..."), body);
    controls->addWidget(save);
    controls->addStretch(1);
    layout->addLayout(controls);
    m_status = new QLabel(body);
    m_status->setObjectName("render_status");
    layout->addWidget(m_status);
    setWidget(body);
    connect(m_exposure, &QDoubleSpinBox::valueChanged, this, &RenderDock::exposureChanged);
    connect(save, &QPushButton::clicked, this, &RenderDock::saveImageRequested);
}

double RenderDock::exposureEv() const { return m_exposure->value(); }

void RenderDock::showResult(const RenderResult& result) {
    const QString preset = QString::fromUtf8(presetName(result.preset).data());
    if (result.image.isNull()) {
        m_status->setText(
            tr("%1: fast model %2 ms (no scene open)").arg(preset).arg(result.brdf_ms, 0, 'f', 1));
        return;
    }
    m_image = result.image;
    m_status->setText(tr("%1: fast model %2 ms, relight tables %3 ms, relight %4 ms")
                          .arg(preset)
                          .arg(result.brdf_ms, 0, 'f', 1)
                          .arg(result.tables_ms, 0, 'f', 1)
                          .arg(result.relight_ms, 0, 'f', 1));
    updatePixmap();
}

void RenderDock::showMessage(const QString& text) { m_status->setText(text); }

void RenderDock::resizeEvent(QResizeEvent* event) {
    QDockWidget::resizeEvent(event);
    updatePixmap();
}

void RenderDock::updatePixmap() {
    if (m_image.isNull()) return;
    m_view->setPixmap(
        QPixmap::fromImage(m_image).scaled(m_view->size(), Qt::KeepAspectRatio, Qt::SmoothTransformation));
}

}  // namespace paintlab::gui
