#pragma once

// Opens a path or a stored series off the UI thread (lw::input, the same code as the CLI), then
// scans what the review needs (value range, histogram, the surface's box for the camera), with
// progress and cancel. Results come back on the UI thread.

#include "review/review_widget.h"

#include <QObject>
#include <QString>
#include <QStringList>
#include <future>
#include <memory>

class QThreadPool;

namespace lw::core {
class CancelToken;
class Progress;
} // namespace lw::core

namespace lw::gui {

struct LoadRequest {
    QString path;       // a path for lw::input::openInput (folder, DICOMDIR, file, phantom:N)
    QStringList files;  // or the files of one stored series (lw::input::openDicomFiles)
    QString seriesUid;  // optional: which series
    double iso = 400.0; // the initial iso-value (clamped to the volume's range)
    // Waited for on the loading thread before the volume is handed over, where valid: the
    // window's probe of the CUDA device. A new review asks it on the UI thread, and while the
    // probe makes its CUDA context (0.2-0.35 s) the ask would block there; a study opened at
    // start (the demo) arrives before the probe ends.
    std::shared_future<void> gpuProbe;
};

// The progress message while a loaded volume waits for LoadRequest::gpuProbe.
inline constexpr const char* kWaitingForGpu = "waiting for the GPU";

class VolumeLoader : public QObject {
    Q_OBJECT
public:
    explicit VolumeLoader(QObject* parent = nullptr);
    ~VolumeLoader() override;

    void start(const LoadRequest& request);
    void cancel();
    bool isRunning() const { return m_cancel != nullptr; }

    // The whole load on the calling thread (worker threads and the CLI-like paths of tests).
    static ReviewSource load(const LoadRequest& request, core::Progress* progress);

signals:
    void progress(double fraction, const QString& message);
    void loaded(std::shared_ptr<lw::gui::ReviewSource> source);
    void failed(const QString& reason);
    void cancelled();
    // A load that was cancelled, or replaced by a newer start(), has ended (loaded, failed or
    // stopped at a check) and what it brought was dropped: nothing of it comes after this.
    void discarded();

private:
    // On the UI thread, once a load's worker has ended: true if `token`'s load is the current
    // one (it is no longer running); otherwise its outcome is dropped, with cancelled() when no
    // newer load runs, then discarded(), and the caller emits nothing.
    bool endCurrent(const std::shared_ptr<core::CancelToken>& token);

    std::shared_ptr<core::CancelToken> m_cancel;
    // Not QThreadPool::globalInstance(): Qt 6.4's raster painting splits fills and image
    // conversions over the global pool and the UI thread waits for them; a load holding one of
    // its threads for minutes stalled every paint (README, "The UI thread only draws").
    // Two threads: a cancelled load may still finish its scans while the next one starts.
    std::unique_ptr<QThreadPool> m_pool;
};

} // namespace lw::gui
