#include "depth_profile_section.h"

#include "depth_profile_editor.h"

#include <QToolButton>
#include <QVBoxLayout>

namespace paintlab::gui {

DepthProfileSection::DepthProfileSection(RecipeDocument* document, int layer, int component, QWidget* parent)
    : QWidget(parent), m_document(document), m_layer(layer), m_component(component) {
    setObjectName(QStringLiteral("depth_profile_section_%1_%2").arg(layer).arg(component));
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    m_button = new QToolButton(this);
    m_button->setObjectName("depth_profile_button");
    m_button->setText(tr("Depth profile..."));
    m_button->setToolTip(tr("How the concentration varies from the top to the bottom of the layer"));
    m_button->setCheckable(true);
    m_button->setToolButtonStyle(Qt::ToolButtonTextBesideIcon);
    m_button->setArrowType(Qt::RightArrow);
    layout->addWidget(m_button, 0, Qt::AlignLeft);
    connect(m_button, &QToolButton::toggled, this, [this, layout](bool open) {
        if (open && m_editor == nullptr) {
            m_editor = new DepthProfileEditor(m_document, m_layer, m_component, this);
            layout->addWidget(m_editor);
        }
        m_button->setArrowType(open ? Qt::DownArrow : Qt::RightArrow);
        if (m_editor != nullptr) m_editor->setVisible(open);
    });
}

bool DepthProfileSection::isOpen() const { return m_button->isChecked(); }

void DepthProfileSection::setOpen(bool open) { m_button->setChecked(open); }

}  // namespace paintlab::gui
