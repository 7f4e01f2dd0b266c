#include "shell/pacs_send.h"

#include "lw/core/error.h"
#include "lw/pacs/pacs_error.h"
#include "lw/pacs/store_scu.h"
#include "lw/report/secondary_capture.h"
#include "review/review_widget.h"

#include <QtConcurrent/QtConcurrentRun>

#ifndef LINEWORK_VERSION
#define LINEWORK_VERSION "unknown"
#endif

namespace lw::gui {
namespace {

std::filesystem::path fsPath(const QString& path) {
    return std::filesystem::path(path.toStdString());
}

// On a pool thread: one association, every object; a failure to associate is the result's error.
PacsSendResult storeObjects(const PacsSendRequest& request,
                            const std::vector<std::pair<QString, QString>>& objects) {
    PacsSendResult result;
    result.node = QString::fromStdString(pacs::describeNode(request.node));
    std::vector<std::filesystem::path> files;
    for (const auto& object : objects)
        files.push_back(fsPath(object.second));
    try {
        const std::vector<pacs::StoreOutcome> outcomes =
            pacs::storeFiles(request.node, files, request.call);
        for (std::size_t i = 0; i < outcomes.size() && i < objects.size(); ++i)
            result.objects.push_back({objects[i].first, QString::fromStdString(outcomes[i].message),
                                      outcomes[i].accepted});
    } catch (const core::Error& error) {
        result.error = QString::fromStdString(error.reason());
    } catch (const std::exception& error) {
        result.error = QString::fromStdString(error.what());
    }
    return result;
}

} // namespace

bool PacsSendResult::allStored() const {
    if (!error.isEmpty() || objects.empty())
        return false;
    for (const PacsSendOutcome& outcome : objects)
        if (!outcome.stored)
            return false;
    return true;
}

QString PacsSendResult::summary() const {
    if (!error.isEmpty())
        return QObject::tr("Nothing was sent to %1: %2").arg(node, error);
    QStringList lines{QObject::tr("%1 answered:").arg(node)};
    for (const PacsSendOutcome& outcome : objects)
        lines << QStringLiteral("%1: %2").arg(outcome.object, outcome.answer);
    return lines.join('\n');
}

PacsSender::PacsSender(QObject* parent) : QObject(parent) {
    connect(&m_watcher, &QFutureWatcher<PacsSendResult>::finished, this, [this] {
        const PacsSendResult result = m_watcher.result();
        m_folder.reset();
        emit finished(result);
    });
}

PacsSender::~PacsSender() {
    m_watcher.waitForFinished();
}

// The Secondary Capture and the PDF report as Encapsulated PDF (one rendering of the panels for
// both), into a new temporary folder; m_objects lists the two DICOM files to send.
QString PacsSender::writeObjects(ReviewWidget& review, const ReportOptions& options,
                                 QWidget* progressParent) {
    m_folder = std::make_unique<QTemporaryDir>();
    if (!m_folder->isValid())
        return tr("Cannot create a temporary folder for the objects to send: %1")
            .arg(m_folder->errorString());
    const QString sc = m_folder->filePath(QStringLiteral("sc"));
    const QString encapsulated = m_folder->filePath(QStringLiteral("report.dcm"));
    if (QString error = exportReviewForPacs(review, sc, encapsulated, options, progressParent);
        !error.isEmpty())
        return error;
    const QString first = sc + '/' + QString::fromStdString(report::secondaryCaptureFileName(1));
    m_objects = {{tr("Secondary Capture"), first}, {tr("Report (Encapsulated PDF)"), encapsulated}};
    return {};
}

QString PacsSender::start(ReviewWidget& review, const PacsSendRequest& request,
                          QWidget* progressParent) {
    if (isSending())
        return tr("A send to the PACS is still running");
    if (request.report.anonymise)
        return tr("An anonymised export cannot be sent to the PACS because it would no longer "
                  "belong to the patient's study");
    if (!review.source().dicom)
        return tr("Only a review of a DICOM series can be sent to the PACS: %1 has no study to "
                  "join")
            .arg(review.source().title);
    if (QString error = writeObjects(review, request.report, progressParent); !error.isEmpty()) {
        m_folder.reset();
        return error;
    }
    m_watcher.setFuture(QtConcurrent::run(
        [request, objects = m_objects] { return storeObjects(request, objects); }));
    return {};
}

} // namespace lw::gui
