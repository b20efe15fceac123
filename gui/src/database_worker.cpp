#include "database_worker.h"

#include <QCoreApplication>
#include <QEvent>

namespace paintlab::gui {

DatabaseWorker::DatabaseWorker(QObject* parent) : QObject(parent) { m_pool.setMaxThreadCount(1); }

// Results still queued for this object are dropped with it (Qt removes the
// posted events of a deleted object).
DatabaseWorker::~DatabaseWorker() { m_pool.waitForDone(); }

void DatabaseWorker::waitForDone() {
    m_pool.waitForDone();
    QCoreApplication::sendPostedEvents(this, QEvent::MetaCall);
}

void DatabaseWorker::runErased(std::function<void(db::Database&)> work, std::function<void()> done,
                               std::function<void(QString)> failed) {
    if (m_file.empty()) {
        failed(tr("No database is open."));
        return;
    }
    if (++m_tasks == 1) emit busyChanged(true);
    m_pool.start(
        [this, file = m_file, work = std::move(work), done = std::move(done), failed = std::move(failed)]() {
            QString error;
            try {
                db::OpenOptions options;
                options.create = false;
                db::Database db = db::Database::open(file, options);
                work(db);
            } catch (const std::exception& e) {
                error = QString::fromUtf8(e.what());
                if (error.isEmpty())
                    error = tr("%1: the operation failed").arg(QString::fromStdString(file.string()));
            } catch (...) {  // nothing may escape a pool task: the program would end
                error = tr("%1: the operation failed with an unknown error")
                            .arg(QString::fromStdString(file.string()));
            }
            QMetaObject::invokeMethod(
                this,
                [this, error, done, failed]() {
                    // The callback first: when busy() turns false its effects are visible.
                    if (error.isEmpty()) {
                        done();
                    } else {
                        failed(error);
                    }
                    finish();
                },
                Qt::QueuedConnection);
        });
}

void DatabaseWorker::finish() {
    if (--m_tasks == 0) emit busyChanged(false);
}

}  // namespace paintlab::gui
