#pragma once

// Runs one blocking engine call (an import, a PACS echo, find or retrieve) on a QtConcurrent pool
// thread and hands its result, or its failure in words, back to `receiver`'s thread as a queued
// call. The caller keeps the QFuture and waits for it before `receiver` goes, so the pool thread
// never outlives what it reports to.

#include "lw/core/error.h"

#include <QFuture>
#include <QMetaObject>
#include <QObject>
#include <QPointer>
#include <QString>
#include <QThreadPool>
#include <QtConcurrent/QtConcurrentRun>
#include <exception>

namespace lw::gui {

// "subject: reason" of a core::Error (a PacsError names the node as AET@HOST:PORT).
inline QString errorText(const core::Error& error) {
    return QStringLiteral("%1: %2").arg(QString::fromStdString(error.subject()),
                                        QString::fromStdString(error.reason()));
}

// `work()` runs on `pool`; then exactly one of onDone(result), onCancelled(), onFailed(text)
// runs on `receiver`'s thread, unless `receiver` is gone by then.
template <typename Work, typename Done, typename Cancelled, typename Failed>
QFuture<void> runInBackground(QThreadPool* pool, QObject* receiver, Work work, Done onDone,
                              Cancelled onCancelled, Failed onFailed) {
    QPointer<QObject> target(receiver);
    const auto post = [target](auto call) {
        QMetaObject::invokeMethod(target.data(), std::move(call), Qt::QueuedConnection);
    };
    return QtConcurrent::run(pool, [post, work, onDone, onCancelled, onFailed] {
        try {
            auto result = work();
            post([onDone, result] { onDone(result); });
        } catch (const core::Cancelled&) {
            post(onCancelled);
        } catch (const core::Error& error) {
            post([onFailed, text = errorText(error)] { onFailed(text); });
        } catch (const std::exception& error) {
            post([onFailed, text = QString::fromStdString(error.what())] { onFailed(text); });
        }
    });
}

// The same on Qt's global pool: for short calls only (an echo, a find). Qt's painting waits on
// that pool; long work has a pool of its own (BackgroundJob).
template <typename Work, typename Done, typename Cancelled, typename Failed>
QFuture<void> runInBackground(QObject* receiver, Work work, Done onDone, Cancelled onCancelled,
                              Failed onFailed) {
    return runInBackground(QThreadPool::globalInstance(), receiver, std::move(work),
                           std::move(onDone), std::move(onCancelled), std::move(onFailed));
}

} // namespace lw::gui
