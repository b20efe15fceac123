#pragma once
// The number field of one recipe parameter in the recipe editor. A plain
// QDoubleSpinBox refuses keys it cannot place ("1e9" became "19"), clamps
// to its range (99999999 became 999) and silently puts back what it cannot
// read (-5); this one lets anything be typed and leaves the judgement to
// checkTypedValue (recipe_parameters.h), which the editor shows at the field.
// It shows the value in the parameter's display unit (volume fractions in
// %) with 6 significant digits. It stays a QDoubleSpinBox: Ctrl+Z from it
// reaches the recipe's undo (undo_shortcut_filter.h).

#include "paintlab/engine/parameters.h"

#include <QDoubleSpinBox>

namespace paintlab::gui {

class ParameterField : public QDoubleSpinBox {
public:
    ParameterField(const ParameterDecl& decl, QWidget* parent = nullptr);

    // Shows the recipe's value (in the recipe's unit) without signals, and
    // forgets what was typed.
    void showValue(double recipe_value);
    // The text typed since the last showValue (without the suffix); empty if
    // nothing was typed (the arrows or the wheel may still have changed value()).
    const QString& typedText() const { return m_typed; }
    // The value shown, in the recipe's unit.
    double recipeValue() const;

    QValidator::State validate(QString& text, int& pos) const override;
    double valueFromText(const QString& text) const override;
    QString textFromValue(double value) const override;

private:
    QString withoutSuffix(const QString& text) const;
    const ParameterDecl* m_decl;
    QString m_typed;
};

}  // namespace paintlab::gui
