#include "lw/studydb/study_importer.h"

#include "lw/core/error.h"
#include "lw/dicom/dicom_scanner.h"
#include "lw/dicom/volume_assembler.h"

#include <QBuffer>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QHash>
#include <algorithm>
#include <filesystem>

namespace lw::studydb {

namespace {

QString qs(const std::string& text) {
    return QString::fromStdString(text);
}

QString folderOf(const std::string& file) {
    return QFileInfo(qs(file)).absolutePath();
}

// Forwards a stage's own 0..1 progress into its slice of the whole import, with the shared
// cancel token so every stage sees a cancel at once.
std::unique_ptr<core::Progress> stageProgress(const core::Progress::Callback& onProgress,
                                              std::shared_ptr<const core::CancelToken> cancel,
                                              double from, double to) {
    core::Progress::Callback callback = [onProgress, from, to](double fraction,
                                                               const std::string& message) {
        if (onProgress)
            onProgress(from + std::clamp(fraction, 0.0, 1.0) * (to - from), message);
    };
    return std::make_unique<core::Progress>(std::move(callback), std::move(cancel));
}

QByteArray toPng(const QImage& image) {
    QByteArray bytes;
    QBuffer buffer(&bytes);
    buffer.open(QIODevice::WriteOnly);
    image.save(&buffer, "PNG");
    return bytes;
}

const dicom::VolumePlan* largestPlan(const dicom::SeriesAssembly& assembly) {
    const dicom::VolumePlan* best = nullptr;
    for (const dicom::VolumePlan& plan : assembly.volumes) {
        const auto voxels = [](const dicom::VolumePlan& p) {
            return std::size_t(p.dims.x) * std::size_t(p.dims.y) * p.slices.size();
        };
        if (!best || voxels(plan) > voxels(*best))
            best = &plan;
    }
    return best;
}

void addWarning(SeriesRecord& record, const QString& text) {
    record.messages.append({SeriesMessage::Kind::Warning, QString(), text});
}

// Geometry warnings of one plan; `prefix` names the volume when the series was split. The plan
// states the tilt, uneven gaps and missing slices itself (what opening the series shows too),
// so each is listed once, in the same words in the browser and the review.
void addPlanWarnings(SeriesRecord& record, const dicom::VolumePlan& plan, const QString& prefix) {
    for (const std::string& warning : plan.warnings)
        addWarning(record, prefix + qs(warning));
}

void fillGeometry(SeriesRecord& record, const dicom::VolumePlan& plan) {
    record.sliceCount = int(plan.slices.size());
    record.dims = {plan.dims.x, plan.dims.y, plan.dims.z};
    const glm::dvec3 spacing = plan.geometry.spacing();
    record.spacing = {spacing.x, spacing.y, spacing.z};
    record.tiltDegrees = plan.tiltDegrees;
    record.unevenGaps = plan.unevenGaps;
    record.minGap = plan.minGap;
    record.maxGap = plan.maxGap;
    record.missingSlices = plan.missingSlices;
}

// A thumbnail that cannot be made is a warning, never a failed import.
void addThumbnail(SeriesRecord& record, const dicom::SeriesInfo& series,
                  const dicom::VolumePlan& plan) {
    try {
        const volume::Volume slice = dicom::loadSlice(series, plan, plan.slices.size() / 2);
        record.thumbnailPng = toPng(makeThumbnail(slice, record.modality == QLatin1String("CT")));
    } catch (const core::Cancelled&) {
        throw;
    } catch (const core::Error& error) {
        addWarning(
            record,
            QStringLiteral("no thumbnail: %1: %2").arg(qs(error.subject()), qs(error.reason())));
    } catch (const std::exception& error) {
        addWarning(record, QStringLiteral("no thumbnail: %1").arg(qs(error.what())));
    }
}

void describeAssembly(SeriesRecord& record, const dicom::SeriesInfo& series,
                      const dicom::SeriesAssembly& assembly) {
    record.volumeCount = int(assembly.volumes.size());
    const bool split = assembly.volumes.size() > 1;
    if (split) {
        QStringList labels;
        for (const dicom::VolumePlan& plan : assembly.volumes)
            labels.append(plan.label.empty() ? QStringLiteral("%1 slices").arg(plan.slices.size())
                                             : qs(plan.label));
        addWarning(record, QStringLiteral("split into %1 volumes: %2")
                               .arg(assembly.volumes.size())
                               .arg(labels.join(QStringLiteral("; "))));
    }
    for (std::size_t i = 0; i < assembly.volumes.size(); ++i) {
        const dicom::VolumePlan& plan = assembly.volumes[i];
        const QString prefix =
            split ? QStringLiteral("volume %1 (%2): ").arg(i + 1).arg(qs(plan.label)) : QString();
        addPlanWarnings(record, plan, prefix);
    }
    for (const std::string& warning : assembly.warnings)
        addWarning(record, qs(warning));
    for (const dicom::FileError& error : assembly.errors)
        record.messages.append({SeriesMessage::Kind::Error, qs(error.file), qs(error.reason)});
    if (series.missingFiles > 0)
        addWarning(record, QStringLiteral("%1 of %2 files referenced by the DICOMDIR are missing")
                               .arg(series.missingFiles)
                               .arg(series.referencedFiles));
    if (assembly.volumes.empty() && !series.instances.empty())
        addWarning(record, QStringLiteral("no volume can be built from this series"));
}

SeriesImport describeSeries(const dicom::PatientInfo& patient, const dicom::StudyInfo& study,
                            const dicom::SeriesInfo& series) {
    SeriesImport item;
    item.patient = {
        qs(patient.patientId), qs(patient.name), qs(patient.birthDate), qs(patient.sex), {}};
    item.study = {qs(study.studyInstanceUid),
                  qs(study.studyId),
                  qs(study.description),
                  qs(study.date),
                  qs(study.time),
                  qs(study.accessionNumber),
                  {}};
    SeriesRecord& record = item.series;
    record.uid = qs(series.seriesInstanceUid);
    record.studyUid = item.study.uid;
    record.modality = qs(series.modality);
    record.description = qs(series.description);
    record.number = series.seriesNumber;
    record.studyDate = item.study.date;
    record.studyTime = item.study.time;
    for (const dicom::InstanceInfo& instance : series.instances) {
        item.files.append(qs(instance.path));
        item.sopInstanceUids.append(qs(instance.sopInstanceUid));
    }
    record.fileCount = int(item.files.size());
    const dicom::SeriesAssembly assembly = dicom::planVolumes(series);
    describeAssembly(record, series, assembly);
    if (const dicom::VolumePlan* plan = largestPlan(assembly)) {
        fillGeometry(record, *plan);
        addThumbnail(record, series, *plan);
    }
    return item;
}

// Files that failed go to the series whose images share their folder; when no single series
// owns the folder they stay import-level problems.
void attachFileErrors(ImportBatch& batch, const dicom::DicomIndex& index) {
    QHash<QString, int> owner; // folder -> batch index, -1 when shared by several series
    for (int i = 0; i < batch.series.size(); ++i)
        for (const QString& file : batch.series[i].files) {
            const QString folder = QFileInfo(file).absolutePath();
            const auto it = owner.constFind(folder);
            if (it == owner.cend())
                owner.insert(folder, i);
            else if (*it != i)
                owner[folder] = -1;
        }
    for (const dicom::FileError& error : index.errors) {
        const int i = owner.value(folderOf(error.file), -1);
        if (i >= 0)
            batch.series[i].series.messages.append(
                {SeriesMessage::Kind::Error, qs(error.file), qs(error.reason)});
        else
            batch.problems.append({qs(error.file), qs(error.reason)});
    }
    for (const std::string& warning : index.warnings)
        batch.problems.append({qs(index.root.string()), qs(warning)});
}

} // namespace

ImportBatch buildImportBatch(const dicom::DicomIndex& index, core::Progress* progress) {
    ImportBatch batch;
    batch.sourceRoot = qs(index.root.string());
    if (progress)
        progress->setTotal(std::max<std::size_t>(index.seriesCount(), 1), "Reading series");
    for (const dicom::PatientInfo& patient : index.patients)
        for (const dicom::StudyInfo& study : patient.studies)
            for (const dicom::SeriesInfo& series : study.series) {
                if (progress)
                    progress->throwIfCancelled();
                batch.series.append(describeSeries(patient, study, series));
                if (progress)
                    progress->step();
            }
    attachFileErrors(batch, index);
    return batch;
}

ImportSummary importStudies(const QString& databasePath, const QString& inputPath,
                            core::Progress::Callback onProgress,
                            std::shared_ptr<const core::CancelToken> cancel) {
    // Opened first: a database that cannot be used fails before minutes of scanning.
    StudyDatabase database(databasePath);
    ImportSummary summary;
    try {
        auto scanProgress = stageProgress(onProgress, cancel, 0.0, 0.5);
        const dicom::DicomIndex index = dicom::scanDicom(
            std::filesystem::path(QFile::encodeName(inputPath).toStdString()), scanProgress.get());
        scanProgress->throwIfCancelled();
        summary.filesExamined = index.filesExamined;

        auto buildProgress = stageProgress(onProgress, cancel, 0.5, 0.95);
        ImportBatch batch = buildImportBatch(index, buildProgress.get());
        batch.sourceRoot = QFileInfo(inputPath).absoluteFilePath();

        auto writeProgress = stageProgress(onProgress, cancel, 0.95, 1.0);
        const WriteResult written = database.write(batch, writeProgress.get());
        summary.seriesAdded = written.seriesAdded;
        summary.seriesUpdated = written.seriesUpdated;
        summary.errors = batch.problems;
        for (const SeriesImport& item : batch.series)
            if (!item.series.messages.isEmpty())
                ++summary.seriesWithWarnings;
    } catch (const core::Cancelled&) {
        const std::size_t examined = summary.filesExamined;
        summary = ImportSummary{};
        summary.filesExamined = examined;
        summary.cancelled = true;
    }
    return summary;
}

} // namespace lw::studydb
