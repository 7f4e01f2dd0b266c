#include "review/volume_loader.h"

#include "lw/core/error.h"
#include "lw/core/progress.h"
#include "lw/core/thread_priority.h"
#include "lw/input/open_input.h"
#include "review/slice_views.h"

#include <QMetaObject>
#include <QPointer>
#include <QThreadPool>
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <new>

namespace lw::gui {

VolumeLoader::VolumeLoader(QObject* parent)
    : QObject(parent), m_pool(std::make_unique<QThreadPool>()) {
    m_pool->setMaxThreadCount(2);
}

// The pool's destructor waits for a load still running: cancelled, it stops at the next slice.
VolumeLoader::~VolumeLoader() {
    cancel();
}

ReviewSource VolumeLoader::load(const LoadRequest& request, core::Progress* progress) {
    input::OpenOptions options;
    if (!request.seriesUid.isEmpty())
        options.seriesUid = request.seriesUid.toStdString();
    input::OpenedVolume opened;
    if (!request.files.isEmpty()) {
        std::vector<std::filesystem::path> files;
        for (const QString& file : request.files)
            files.emplace_back(file.toStdString());
        opened = input::openDicomFiles(files, options, progress);
    } else {
        opened = input::openInput(request.path.toStdString(), options, progress);
    }
    if (progress)
        progress->throwIfCancelled();
    if (opened.volume.dims().z < 2)
        throw core::Error(opened.source, "a single slice holds no iso-surface; a review needs "
                                         "at least two slices");
    ReviewSource source;
    source.title = QString::fromStdString(opened.description);
    source.seriesUid = QString::fromStdString(opened.seriesUid);
    source.dicom = opened.dicom;
    source.valueUnit =
        valueUnit(opened.dicom ? QString::fromStdString(opened.dicom->modality) : QString(),
                  request.path.startsWith(QLatin1String("phantom:")));
    for (const std::string& warning : opened.warnings)
        source.warnings << QString::fromStdString(warning);
    source.range = opened.volume.realRange();
    source.histogram = opened.volume.histogram(256);
    source.initialIso = std::clamp(request.iso, source.range.min, source.range.max);
    if (request.iso < source.range.min || request.iso > source.range.max)
        source.initialIso = 0.5 * (source.range.min + source.range.max);
    source.bounds = render::surfaceBounds(opened.volume, source.initialIso);
    source.volume = std::make_shared<const volume::Volume>(std::move(opened.volume));
    return source;
}

void VolumeLoader::start(const LoadRequest& request) {
    cancel();
    auto token = std::make_shared<core::CancelToken>();
    m_cancel = token;
    QPointer<VolumeLoader> self(this);
    // Results and progress hop back to the UI thread; a loader destroyed meanwhile gets none.
    auto post = [self](auto function) {
        QMetaObject::invokeMethod(
            self.data(),
            [self, function] {
                if (self)
                    function(*self);
            },
            Qt::QueuedConnection);
    };
    m_pool->start([request, token, post] {
        core::lowerCurrentThreadToBackground();
        // Whole percents only: every step a repaint of the status bar and the X server's work
        // besides, a thousand times a load; a progress bar shows no finer steps. Calls of a
        // Progress's callback never overlap, so the lambda's own state needs no lock.
        core::Progress progress(
            [post, shownPercent = -1,
             shownMessage = std::string()](double fraction, const std::string& message) mutable {
                const int percent = int(fraction * 100.0);
                if (percent == shownPercent && message == shownMessage)
                    return;
                shownPercent = percent;
                shownMessage = message;
                post([fraction, text = QString::fromStdString(message)](VolumeLoader& loader) {
                    emit loader.progress(fraction, text);
                });
            },
            token);
        try {
            auto source = std::make_shared<ReviewSource>(load(request, &progress));
            if (request.gpuProbe.valid() &&
                request.gpuProbe.wait_for(std::chrono::seconds(0)) != std::future_status::ready) {
                progress.report(1.0, kWaitingForGpu);
                request.gpuProbe.wait();
            }
            post([source, token](VolumeLoader& loader) {
                if (loader.endCurrent(token))
                    emit loader.loaded(source);
            });
        } catch (const core::Cancelled&) {
            post([token](VolumeLoader& loader) {
                if (loader.endCurrent(token))
                    emit loader.cancelled();
            });
        } catch (const std::bad_alloc&) {
            post([token](VolumeLoader& loader) {
                if (loader.endCurrent(token))
                    emit loader.failed(tr("out of memory while loading the volume"));
            });
        } catch (const std::exception& error) {
            post([token, reason = QString::fromStdString(error.what())](VolumeLoader& loader) {
                if (loader.endCurrent(token))
                    emit loader.failed(reason);
            });
        }
    });
}

// A cancelled or replaced load's failure is dropped too: it would otherwise report an error for
// something the user no longer asked for, over the newer load's progress.
bool VolumeLoader::endCurrent(const std::shared_ptr<core::CancelToken>& token) {
    if (m_cancel == token) {
        m_cancel.reset();
        return true;
    }
    if (!m_cancel) // no newer load is running: the cancel gets its answer
        emit cancelled();
    emit discarded();
    return false;
}

void VolumeLoader::cancel() {
    if (m_cancel)
        m_cancel->cancel();
    m_cancel.reset();
}

} // namespace lw::gui
