#pragma once
// A small chart of one spectrum over wavelength, drawn with QPainter: the
// ingredient browser's preview (the VTK plots under plots/ are for the paint's
// optics). Tabulated spectra are drawn as the linear interpolation the engine
// uses with their samples marked; a constant one as a flat line over the
// visible range. Axes with rounded ticks, the quantity and unit as title and
// as the value axis' label (drawn upright along it).

#include <QRect>
#include <QString>
#include <QWidget>

#include <vector>

namespace paintlab::gui {

class SpectrumChart : public QWidget {
    Q_OBJECT
public:
    explicit SpectrumChart(QWidget* parent = nullptr);

    // wavelengths_nm empty or of size one with values of size one: a constant.
    void setSpectrum(const QString& title, const QString& unit, std::vector<double> wavelengths_nm,
                     std::vector<double> values);
    void clear();
    bool hasSpectrum() const { return !m_values.empty(); }
    const QString& title() const { return m_title; }
    // The value axis' label ("sigma_a (1/µm)"), and where the last paint drew
    // it (empty if it did not fit or nothing was drawn).
    QString valueAxisTitle() const;
    QRect valueAxisTitleRect() const { return m_value_title_rect; }

    QSize sizeHint() const override { return {420, 260}; }
    // Small enough not to raise the main window's minimum height (docks stack).
    QSize minimumSizeHint() const override { return {200, 120}; }

protected:
    void paintEvent(QPaintEvent* event) override;

private:
    QString m_title;
    QString m_unit;
    std::vector<double> m_wavelengths_nm;
    std::vector<double> m_values;
    QRect m_value_title_rect;
};

// Up to about `count` round tick values covering [lo, hi] (1, 2, 5 times a power of ten apart).
std::vector<double> niceTicks(double lo, double hi, int count);

}  // namespace paintlab::gui
