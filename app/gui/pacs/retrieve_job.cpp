#include "pacs/retrieve_job.h"

#include "lw/studydb/retrieved_files.h"

namespace lw::gui {

namespace {

RetrieveOutcome outcomeOf(const pacs::PacsNode& node, const pacs::RetrieveRequest& request,
                          const pacs::RetrieveResult& result) {
    RetrieveOutcome outcome;
    outcome.nodeName = QString::fromStdString(node.name);
    outcome.studyUid = QString::fromStdString(request.studyUid);
    outcome.seriesUid = QString::fromStdString(request.seriesUid);
    outcome.instances = int(result.instances);
    outcome.transferred = int(result.transferred);
    outcome.skipped = int(result.skipped);
    outcome.failed = int(result.failed);
    outcome.cancelled = result.cancelled;
    outcome.message = QString::fromStdString(result.message);
    return outcome;
}

// The store's folder of what was asked for: STORE/<study>[/<series>].
QString requestFolder(const pacs::RetrieveRequest& request) {
    std::filesystem::path folder = request.store / request.studyUid;
    if (!request.seriesUid.empty())
        folder /= request.seriesUid;
    return QString::fromStdString(folder.string());
}

} // namespace

RetrieveJob::RetrieveJob(QString databasePath, QObject* parent)
    : BackgroundJob(std::move(databasePath), parent) {
    qRegisterMetaType<RetrieveOutcome>();
}

RetrieveJob::~RetrieveJob() {
    cancelAndWait();
}

bool RetrieveJob::start(const pacs::PacsNode& node, const pacs::RetrieveRequest& request,
                        const pacs::CallOptions& options) {
    // `this` outlives the pool thread: the destructor waits for it.
    const auto work = [this, node, request, options, databasePath = databasePath()](
                          const std::shared_ptr<core::CancelToken>& cancel) {
        const auto onInstance = [this](const pacs::RetrieveProgress& progress) {
            emit instanceArrived(int(progress.done), int(progress.toTransfer));
        };
        const pacs::RetrieveResult result =
            pacs::retrieve(node, request, options, onInstance, cancel.get());
        RetrieveOutcome outcome = outcomeOf(node, request, result);
        if (result.files.empty())
            return outcome;
        try {
            studydb::registerRetrievedFolder(databasePath, requestFolder(request));
        } catch (const core::Error& error) {
            const QString registering = errorText(error);
            outcome.message = outcome.message.isEmpty()
                                  ? registering
                                  : outcome.message + QStringLiteral("; ") + registering;
        }
        return outcome;
    };
    return startRun(
        work, [this](const RetrieveOutcome& outcome) { emit finished(outcome); },
        [this, node, request] {
            // Cancelled while the instances were being listed: nothing arrived.
            RetrieveOutcome outcome = outcomeOf(node, request, {});
            outcome.cancelled = true;
            emit finished(outcome);
        },
        [this](const QString& message) { emit failed(message); });
}

} // namespace lw::gui
