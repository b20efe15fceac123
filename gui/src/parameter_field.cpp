#include "parameter_field.h"

#include "recipe_parameters.h"
#include "wheel_scrolls_form.h"

#include "paintlab/engine/io/number_format.h"

#include <QLineEdit>
#include <QSignalBlocker>

#include <limits>

namespace paintlab::gui {

ParameterField::ParameterField(const ParameterDecl& decl, QWidget* parent)
    : QDoubleSpinBox(parent), m_decl(&decl) {
    // No range and no rounding of its own: what was typed is judged by
    // checkTypedValue, and a value is shown to 6 significant digits.
    setDecimals(17);
    setRange(-std::numeric_limits<double>::max(), std::numeric_limits<double>::max());
    const DisplayUnit unit = displayUnit(decl);
    if (!unit.unit.empty()) setSuffix(" " + QString::fromStdString(unit.unit));
    // Its size for the longest value it will usually show, not for its range's.
    setMinimumWidth(fontMetrics().horizontalAdvance(QStringLiteral("0.000000 ") + suffix()) + 30);
    letWheelScrollTheForm(this);
    connect(lineEdit(), &QLineEdit::textEdited, this,
            [this](const QString& text) { m_typed = withoutSuffix(text); });
}

QString ParameterField::withoutSuffix(const QString& text) const {
    return !suffix().isEmpty() && text.endsWith(suffix()) ? text.chopped(suffix().size()) : text;
}

void ParameterField::showValue(double recipe_value) {
    const QSignalBlocker block(this);
    setValue(recipe_value * displayUnit(*m_decl).scale);
    m_typed.clear();
}

double ParameterField::recipeValue() const { return value() / displayUnit(*m_decl).scale; }

QValidator::State ParameterField::validate(QString& /*text*/, int& /*pos*/) const {
    // Anything may be typed: the editor judges it when it is committed.
    return QValidator::Acceptable;
}

double ParameterField::valueFromText(const QString& text) const {
    const TypedValue typed = checkTypedValue(*m_decl, withoutSuffix(text).toStdString());
    // Not a number (yet): the value stays; the editor says so when committed.
    if (typed.verdict == TypedValue::Verdict::NotANumber) return value();
    return typed.value * displayUnit(*m_decl).scale;
}

QString ParameterField::textFromValue(double value) const {
    return QString::fromStdString(io::formatNumber(value));
}

}  // namespace paintlab::gui
