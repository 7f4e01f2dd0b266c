#pragma once

// Feeds RenderWorker on its own thread: at most one request runs, at most one waits (the newest
// replaces an older waiting one). A request for other settings cancels the running one (its
// result would be dropped); one for another iso-value lets it finish, so that while the slider
// is dragged the panels show each frame that completes and then the newest value, instead of
// nothing until the drag stops. Results arrive on the UI thread through frameReady().

#include "review/render_worker.h"

#include <QObject>
#include <QPointer>
#include <QThread>
#include <functional>
#include <memory>
#include <optional>

class QOffscreenSurface;

namespace lw::gui {

class RenderScheduler : public QObject {
    Q_OBJECT
public:
    explicit RenderScheduler(std::shared_ptr<const volume::Volume> volume,
                             QObject* parent = nullptr);
    ~RenderScheduler() override;

    // Queues `request` (its id is assigned here and returned).
    std::uint64_t request(FrameRequest request);
    bool isBusy() const { return m_running.has_value(); }
    // Renders an export's panels on the worker thread, after the frame in flight, and waits for
    // them: from any thread but the worker's (an export's pool thread). Thread-safe; throws
    // core::Error (also when the review has gone meanwhile).
    std::function<std::pair<QImage, QImage>(const PanelRenderJob&, PanelVectors*)>
    panelRenderer() const;

signals:
    void frameReady(std::shared_ptr<const lw::gui::FrameResult> result);
    void busyChanged(bool busy);

private:
    void dispatch(FrameRequest request);
    void finished(std::shared_ptr<const FrameResult> result);

    // For the worker's GL context (silhouette textures): Qt makes offscreen surfaces on the UI
    // thread only; made at the first request that wants one, destroyed after the worker stopped.
    std::unique_ptr<QOffscreenSurface> m_textureSurface;
    std::shared_ptr<RenderWorker> m_worker;
    QThread m_thread;
    QObject* m_threadContext = nullptr; // lives in m_thread; queued calls run there
    std::uint64_t m_nextId = 0;
    struct Running {
        std::uint64_t settingsGeneration;
        std::shared_ptr<core::CancelToken> cancel;
    };
    std::optional<Running> m_running;
    std::optional<FrameRequest> m_waiting;
};

} // namespace lw::gui
