#include "render_dock.h"

#include "comparison_view.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QVBoxLayout>

namespace paintlab::gui {

namespace {

QString timesText(const RenderResult& result) {
    const QString preset = QString::fromUtf8(presetName(result.preset).data());
    if (result.image.isNull())
        return RenderDock::tr("%1: fast model %2 ms (no scene open)")
            .arg(preset)
            .arg(result.brdf_ms, 0, 'f', 1);
    return RenderDock::tr("%1: fast model %2 ms, relight tables %3 ms, relight %4 ms")
        .arg(preset)
        .arg(result.brdf_ms, 0, 'f', 1)
        .arg(result.tables_ms, 0, 'f', 1)
        .arg(result.relight_ms, 0, 'f', 1);
}

}  // namespace

RenderDock::RenderDock(QWidget* parent) : QWidget(parent) {
    setObjectName("render");
    QWidget* body = this;
    auto* layout = new QVBoxLayout(body);
    layout->setContentsMargins(4, 4, 4, 2);
    m_view = new ComparisonView(body);
    // The first start's empty state says what to do.
    m_view->setPlaceholder(
        tr("No recipe open.\nPick one in the Recipes list,\nor File > Open recipe file..."));
    layout->addWidget(m_view, 1);
    auto* compare = new QHBoxLayout();
    m_mode = new QComboBox(body);
    m_mode->setObjectName("compare_mode");
    m_mode->addItem(tr("Single"));
    m_mode->addItem(tr("Side by side"));
    m_mode->addItem(tr("Split"));
    m_mode->setToolTip(tr("Compare the edited recipe (left) with another version (right): pick one in the "
                          "Versions dock, or pin the current recipe"));
    compare->addWidget(m_mode);
    m_pin = new QPushButton(tr("Pin current"), body);
    m_pin->setToolTip(tr("Keep the current recipe's render as the comparison"));
    m_pin->setObjectName("pin_comparison");
    compare->addWidget(m_pin);
    m_clear = new QPushButton(tr("Clear comparison"), body);
    m_clear->setToolTip(tr("Show the edited recipe alone"));
    m_clear->setObjectName("clear_comparison");
    m_clear->setEnabled(false);
    compare->addWidget(m_clear);
    compare->addStretch(1);
    auto* controls = compare;  // one row under the picture: compare, exposure, save
    controls->addWidget(new QLabel(tr("Exposure"), body));
    m_exposure = new QDoubleSpinBox(body);
    m_exposure->setRange(-8.0, 8.0);
    m_exposure->setSingleStep(0.25);
    m_exposure->setSuffix(" EV");
    m_exposure->setObjectName("exposure");
    controls->addWidget(m_exposure);
    auto* save = new QPushButton(tr("Save image..."), body);
    save->setToolTip(tr("Saves what is shown: a comparison with its labels"));
    controls->addWidget(save);
    layout->addLayout(controls);
    m_status = new QLabel(body);
    m_status->setObjectName("render_status");
    // The times change with every recompute: their text must not resize the dock.
    m_status->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);
    layout->addWidget(m_status);
    m_comparison_status = new QLabel(body);
    m_comparison_status->setObjectName("comparison_status");
    m_comparison_status->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);
    m_comparison_status->hide();
    layout->addWidget(m_comparison_status);
    connect(m_exposure, &QDoubleSpinBox::valueChanged, this, &RenderDock::exposureChanged);
    connect(save, &QPushButton::clicked, this, &RenderDock::saveImageRequested);
    connect(m_pin, &QPushButton::clicked, this, &RenderDock::pinCurrentRequested);
    connect(m_clear, &QPushButton::clicked, this, &RenderDock::clearComparisonRequested);
    connect(m_mode, &QComboBox::currentIndexChanged, this, &RenderDock::updateView);
    connect(m_view, &ComparisonView::dividerDragged, this, &RenderDock::setSplitFraction);
}

double RenderDock::exposureEv() const { return m_exposure->value(); }

QSize RenderDock::viewPixels() const { return m_view->size() * m_view->devicePixelRatio(); }

void RenderDock::showResult(const RenderResult& result) {
    m_view->setPlaceholder(tr("No image yet"));  // a recipe is open: a scene is still to come
    m_status->setText(timesText(result));
    if (result.image.isNull()) return;
    m_image = result.image;
    updateView();
}

void RenderDock::showMessage(const QString& text) { m_status->setText(text); }

void RenderDock::setCurrentLabel(const QString& label) {
    m_current_label = label;
    updateView();
}

void RenderDock::setComparisonLabel(const QString& label) {
    m_comparison_label = label;
    m_comparison = {};  // the old version's image is not this one's
    m_clear->setEnabled(true);
    m_comparison_status->setText(tr("Comparison %1: rendering...").arg(label));
    m_comparison_status->show();
    // Picking a version to compare with means wanting to see it.
    if (mode() == CompareMode::Single) setMode(CompareMode::SideBySide);
    updateView();
}

void RenderDock::showComparison(const RenderResult& result) {
    if (m_comparison_label.isEmpty()) return;  // cleared while it rendered
    m_comparison_status->setText(tr("Comparison %1: %2").arg(m_comparison_label, timesText(result)));
    if (result.image.isNull()) return;
    m_comparison = result.image;
    updateView();
}

void RenderDock::clearComparison() {
    m_comparison = {};
    m_comparison_label.clear();
    m_clear->setEnabled(false);
    m_comparison_status->hide();
    setMode(CompareMode::Single);
    updateView();
}

CompareMode RenderDock::mode() const { return static_cast<CompareMode>(m_mode->currentIndex()); }

void RenderDock::setMode(CompareMode mode) { m_mode->setCurrentIndex(static_cast<int>(mode)); }

void RenderDock::setSplitFraction(double fraction) {
    m_split = std::clamp(fraction, 0.0, 1.0);
    updateView();
}

QImage RenderDock::shownPixels() const {
    switch (mode()) {
    case CompareMode::SideBySide:
        return m_comparison.isNull() ? m_image : sideBySideImage(m_image, m_comparison);
    case CompareMode::Split: {
        const QImage split = splitImage(m_image, m_comparison, splitColumn(m_image.width(), m_split));
        return split.isNull() ? m_image : split;  // no comparison (yet), or another map's size
    }
    case CompareMode::Single:
        break;
    }
    return m_image;
}

QImage RenderDock::imageToSave() const {
    const bool comparing = mode() != CompareMode::Single && !m_comparison.isNull();
    if (!comparing) return m_image;
    const int divider = mode() == CompareMode::Split ? splitColumn(m_image.width(), m_split) : -1;
    return captionedImage(shownPixels(), m_current_label, m_comparison_label, divider);
}

void RenderDock::updateView() {
    const bool comparing = mode() != CompareMode::Single && !m_comparison.isNull();
    const QImage pixels = shownPixels();
    const bool split = comparing && mode() == CompareMode::Split && pixels.size() == m_image.size();
    m_view->setPicture(pixels, comparing ? m_current_label : QString(),
                       comparing ? m_comparison_label : QString(),
                       split ? splitColumn(m_image.width(), m_split) : -1);
    // The labels on the picture are shortened to fit; the tooltip has them whole.
    m_view->setToolTip(comparing ? tr("Left: %1\nRight: %2").arg(m_current_label, m_comparison_label)
                                 : QString());
    if (mode() != CompareMode::Single && m_comparison_label.isEmpty())
        m_comparison_status->setText(tr("No comparison: pick a version in the Versions dock "
                                        "(Compare in render) or pin the current recipe"));
    m_comparison_status->setVisible(mode() != CompareMode::Single || !m_comparison_label.isEmpty());
}

}  // namespace paintlab::gui
