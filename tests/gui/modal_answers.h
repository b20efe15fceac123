#pragma once
// Answers the modal dialogs a GUI test makes the workstation open (they run
// their own event loop, so the test cannot answer them after the call): the
// expected dialogs, by object name and in order, each with what to do. A
// modal dialog nobody expected is recorded and rejected, so a test never hangs.

#include <QApplication>
#include <QDialog>
#include <QInputDialog>
#include <QMessageBox>
#include <QObject>
#include <QPointer>
#include <QPushButton>
#include <QString>
#include <QStringList>
#include <QTimer>
#include <QWidget>

#include <deque>
#include <functional>
#include <utility>

namespace paintlab::test {

class ModalAnswers : public QObject {
public:
    using Answer = std::function<void(QWidget*)>;

    ModalAnswers() {
        m_timer.setInterval(20);
        connect(&m_timer, &QTimer::timeout, this, &ModalAnswers::poll);
        m_timer.start();
    }
    void expect(const QString& name, Answer answer) { m_queue.push_back({name, std::move(answer)}); }
    bool done() const { return m_queue.empty(); }
    // The names of the modal dialogs that came unexpected (rejected).
    const QStringList& unexpected() const { return m_unexpected; }

    // Answers: a standard button of a message box, a button by its text, a text typed and accepted.
    static Answer click(QMessageBox::StandardButton button) {
        return [button](QWidget* w) { qobject_cast<QMessageBox*>(w)->button(button)->click(); };
    }
    static Answer clickText(const QString& text) {
        return [text](QWidget* w) {
            for (QAbstractButton* b : qobject_cast<QMessageBox*>(w)->buttons())
                if (b->text() == text) b->click();
        };
    }
    static Answer type(const QString& text, QString* shown = nullptr) {
        return [text, shown](QWidget* w) {
            auto* dialog = qobject_cast<QInputDialog*>(w);
            if (shown != nullptr) *shown = dialog->textValue();
            dialog->setTextValue(text);
            dialog->accept();
        };
    }

private:
    struct Step {
        QString name;
        Answer answer;
    };
    void poll() {
        QWidget* modal = QApplication::activeModalWidget();
        if (modal == nullptr || modal == m_last) return;  // none, or the one answered, still closing
        m_last = modal;
        if (m_queue.empty() || modal->objectName() != m_queue.front().name) {
            m_unexpected << modal->objectName();
            if (auto* dialog = qobject_cast<QDialog*>(modal)) {
                dialog->reject();
            } else {
                modal->close();
            }
            return;
        }
        const Step step = m_queue.front();
        m_queue.pop_front();
        step.answer(modal);
    }

    QTimer m_timer;
    std::deque<Step> m_queue;
    QPointer<QWidget> m_last;
    QStringList m_unexpected;
};

}  // namespace paintlab::test
