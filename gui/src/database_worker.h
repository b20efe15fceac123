#pragma once
// Database and file work off the GUI thread: importing a file of up to
// 64 MiB, exporting every ingredient or writing a production sheet can take
// far longer than the 50 ms the GUI thread may block. Each task runs on one
// worker thread (tasks run in the order given) with its own connection to
// the database file (a connection belongs to one thread, database.h); the
// result or the error message comes back on the GUI thread. A worker that is
// destroyed waits for its running task and drops the results not delivered.

#include "paintlab/database/database.h"

#include <QObject>
#include <QString>
#include <QThreadPool>

#include <exception>
#include <filesystem>
#include <functional>
#include <memory>
#include <utility>

namespace paintlab::gui {

class DatabaseWorker : public QObject {
    Q_OBJECT
public:
    explicit DatabaseWorker(QObject* parent = nullptr);
    ~DatabaseWorker() override;
    DatabaseWorker(const DatabaseWorker&) = delete;
    DatabaseWorker& operator=(const DatabaseWorker&) = delete;
    DatabaseWorker(DatabaseWorker&&) = delete;
    DatabaseWorker& operator=(DatabaseWorker&&) = delete;

    // The database file the tasks open (empty: no database; run() then fails at once).
    void setFile(std::filesystem::path file) { m_file = std::move(file); }
    const std::filesystem::path& file() const { return m_file; }
    // True while a task runs or waits, until its result has been delivered.
    bool busy() const { return m_tasks > 0; }

    // work(db) runs on the worker thread; done(result) or failed(message) then
    // runs on the GUI thread. The message is the exception's text (it names
    // the file, the record and the field).
    template <class Result> void run(std::function<Result(db::Database&)> work,
                                     std::function<void(Result)> done,
                                     const std::function<void(QString)>& failed) {
        auto result = std::make_shared<Result>();
        runErased([work = std::move(work), result](db::Database& db) { *result = work(db); },
                  [done = std::move(done), result]() { done(std::move(*result)); }, failed);
    }

    // Waits for every task and delivers the results (for tests and shutdown).
    void waitForDone();

signals:
    void busyChanged(bool busy);

private:
    void runErased(std::function<void(db::Database&)> work, std::function<void()> done,
                   std::function<void(QString)> failed);
    void finish();

    std::filesystem::path m_file;
    int m_tasks = 0;
    QThreadPool m_pool;  // one thread: tasks run in order, writes never race each other
};

}  // namespace paintlab::gui
