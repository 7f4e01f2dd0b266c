#include "review/render_scheduler.h"

#include "lw/core/error.h"
#include "lw/core/thread_priority.h"

#include <QMetaObject>
#include <QOffscreenSurface>
#include <QOpenGLContext>
#include <QPointer>
#include <exception>

namespace lw::gui {

RenderScheduler::RenderScheduler(std::shared_ptr<const volume::Volume> volume, QObject* parent)
    : QObject(parent), m_worker(std::make_shared<RenderWorker>(std::move(volume))) {
    m_thread.setObjectName("lw.render.worker");
    m_threadContext = new QObject;
    m_threadContext->moveToThread(&m_thread);
    connect(&m_thread, &QThread::finished, m_threadContext, &QObject::deleteLater);
    m_thread.start();
    // Frames are background work: the UI thread and the X server go first (thread_priority.h).
    QMetaObject::invokeMethod(
        m_threadContext, [] { core::lowerCurrentThreadToBackground(); }, Qt::QueuedConnection);
}

RenderScheduler::~RenderScheduler() {
    m_waiting.reset();
    if (m_running)
        m_running->cancel->cancel();
    // The worker's renderers are released on its own thread (a headless GL context belongs to
    // the thread that made it); the queued call runs after the one in flight.
    std::shared_ptr<RenderWorker> worker = m_worker;
    QMetaObject::invokeMethod(
        m_threadContext, [worker] { worker->release(); }, Qt::BlockingQueuedConnection);
    m_thread.quit();
    m_thread.wait();
}

std::uint64_t RenderScheduler::request(FrameRequest request) {
    request.id = ++m_nextId;
    request.requested = std::chrono::steady_clock::now();
    if ((request.silhouetteToTexture || request.sharedGl) && !m_textureSurface &&
        QOpenGLContext::globalShareContext()) {
        m_textureSurface = std::make_unique<QOffscreenSurface>();
        m_textureSurface->setFormat(QOpenGLContext::globalShareContext()->format());
        m_textureSurface->create();
    }
    request.textureSurface = m_textureSurface.get();
    if (m_running) {
        if (m_running->settingsGeneration != request.settingsGeneration)
            m_running->cancel->cancel();
        m_waiting = std::move(request);
        return m_nextId;
    }
    dispatch(std::move(request));
    return m_nextId;
}

std::function<std::pair<QImage, QImage>(const PanelRenderJob&, PanelVectors*)>
RenderScheduler::panelRenderer() const {
    QPointer<QObject> threadContext(m_threadContext);
    std::shared_ptr<RenderWorker> worker = m_worker;
    QOffscreenSurface* surface = m_textureSurface.get();
    return [threadContext, worker, surface](const PanelRenderJob& job, PanelVectors* vectors) {
        std::pair<QImage, QImage> panels;
        std::exception_ptr failure;
        const bool ran = QMetaObject::invokeMethod(
            threadContext.data(),
            [&] {
                try {
                    panels = worker->renderPanels(job, surface, vectors);
                } catch (...) {
                    failure = std::current_exception();
                }
            },
            Qt::BlockingQueuedConnection);
        if (!ran)
            throw core::Error("export", "the review was closed while exporting");
        if (failure)
            std::rethrow_exception(failure);
        return panels;
    };
}

void RenderScheduler::dispatch(FrameRequest request) {
    m_running = Running{request.settingsGeneration, request.cancel};
    emit busyChanged(true);
    QPointer<RenderScheduler> self(this);
    std::shared_ptr<RenderWorker> worker = m_worker;
    QMetaObject::invokeMethod(
        m_threadContext,
        [self, worker, request = std::move(request)] {
            auto result = std::make_shared<const FrameResult>(worker->run(request));
            QMetaObject::invokeMethod(
                self.data(),
                [self, result] {
                    if (self)
                        self->finished(result);
                },
                Qt::QueuedConnection);
        },
        Qt::QueuedConnection);
}

void RenderScheduler::finished(std::shared_ptr<const FrameResult> result) {
    m_running.reset();
    if (m_waiting) {
        FrameRequest next = std::move(*m_waiting);
        m_waiting.reset();
        dispatch(std::move(next));
    } else {
        emit busyChanged(false);
    }
    if (!result->cancelled)
        emit frameReady(result);
}

} // namespace lw::gui
