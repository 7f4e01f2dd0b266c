#include "instance_grouping.h"

#include "dicom_file.h"
#include "lw/core/error.h"
#include "lw/core/parallel.h"
#include "scan_paths.h"

#include <algorithm>
#include <dcmtk/dcmdata/dcuid.h>
#include <map>

namespace fs = std::filesystem;

namespace lw::dicom::detail {

namespace {

void setIfEmpty(std::string& target, const std::string& value) {
    if (target.empty())
        target = value;
}

} // namespace

HeaderResults readHeaders(const std::vector<fs::path>& files, core::Progress* progress,
                          const core::ImportLimits& limits) {
    enum class Outcome { Pending, Instance, Error, Dicomdir };
    struct Slot {
        Outcome outcome = Outcome::Pending;
        InstanceInfo instance;
        std::string reason;
    };
    std::vector<Slot> slots(files.size());
    if (progress)
        progress->setTotal(files.size(), "Reading DICOM headers");
    core::parallelFor(files.size(), [&](std::size_t i) {
        if (progress)
            progress->throwIfCancelled();
        Slot& slot = slots[i];
        const fs::path& path = files[i];
        try {
            if (isNamedDicomdir(path) && safeIsDicomdir(path)) {
                slot.outcome = Outcome::Dicomdir;
            } else {
                slot.instance = readInstanceHeader(path, limits);
                slot.outcome = slot.instance.sopClassUid == UID_MediaStorageDirectoryStorage
                                   ? Outcome::Dicomdir
                                   : Outcome::Instance;
            }
        } catch (const core::Error& error) {
            // A Media Storage Directory file the header reader refused is still a DICOMDIR, not
            // a broken image.
            if (safeIsDicomdir(path)) {
                slot.outcome = Outcome::Dicomdir;
            } else {
                slot.outcome = Outcome::Error;
                slot.reason = error.reason().empty() ? error.what() : error.reason();
            }
        } catch (const std::bad_alloc&) {
            slot.outcome = Outcome::Error;
            slot.reason = "out of memory while reading the header";
        } catch (const core::Cancelled&) {
            throw;
        } catch (const std::exception& error) {
            slot.outcome = Outcome::Error;
            slot.reason = error.what();
        }
        if (progress)
            progress->step();
    });
    HeaderResults results;
    for (std::size_t i = 0; i < files.size(); ++i) {
        Slot& slot = slots[i];
        switch (slot.outcome) {
        case Outcome::Instance:
            if (slot.instance.path.empty())
                slot.instance.path = files[i].string();
            results.instances.push_back(std::move(slot.instance));
            break;
        case Outcome::Error:
            results.errors.push_back({files[i].string(), slot.reason});
            break;
        case Outcome::Dicomdir:
            results.skippedDicomdirs.push_back(files[i].string());
            break;
        case Outcome::Pending:
            break;
        }
    }
    return results;
}

namespace {

// The same object twice (copied folders, a file and its re-encoded twin): the first by path is
// kept, the others are reported. Sorted by path first: the parallel read and the walk order must
// not leak out.
std::vector<InstanceInfo> keepFirstOfEachUid(std::vector<InstanceInfo> instances,
                                             std::vector<std::string>& warnings) {
    std::sort(instances.begin(), instances.end(),
              [](const InstanceInfo& a, const InstanceInfo& b) { return a.path < b.path; });
    std::map<std::string, std::string> firstPathOfUid;
    std::vector<InstanceInfo> unique;
    unique.reserve(instances.size());
    for (auto& instance : instances) {
        if (!instance.sopInstanceUid.empty()) {
            auto [it, inserted] =
                firstPathOfUid.try_emplace(instance.sopInstanceUid, instance.path);
            if (!inserted) {
                warnings.push_back("duplicate SOPInstanceUID " + instance.sopInstanceUid + ": " +
                                   instance.path + " ignored, " + it->second + " kept");
                continue;
            }
        }
        unique.push_back(std::move(instance));
    }
    return unique;
}

} // namespace

std::vector<PatientInfo> groupInstances(std::vector<InstanceInfo> instances,
                                        std::vector<std::string>& warnings) {
    std::vector<InstanceInfo> unique = keepFirstOfEachUid(std::move(instances), warnings);
    std::map<std::string, PatientInfo> patients;
    std::map<std::string, std::map<std::string, StudyInfo>> studies;
    std::map<std::string, std::map<std::string, std::map<std::string, SeriesInfo>>> series;
    std::size_t withoutSeriesUid = 0;
    for (auto& instance : unique) {
        const std::string patientKey = instance.patientId + '\x1f' + instance.patientName;
        PatientInfo& patient = patients[patientKey];
        setIfEmpty(patient.patientId, instance.patientId);
        setIfEmpty(patient.name, instance.patientName);
        setIfEmpty(patient.birthDate, instance.patientBirthDate);
        setIfEmpty(patient.sex, instance.patientSex);

        StudyInfo& study = studies[patientKey][instance.studyInstanceUid];
        setIfEmpty(study.studyInstanceUid, instance.studyInstanceUid);
        setIfEmpty(study.studyId, instance.studyId);
        setIfEmpty(study.description, instance.studyDescription);
        setIfEmpty(study.date, instance.studyDate);
        setIfEmpty(study.time, instance.studyTime);
        setIfEmpty(study.accessionNumber, instance.accessionNumber);

        if (instance.seriesInstanceUid.empty())
            ++withoutSeriesUid;
        SeriesInfo& s = series[patientKey][instance.studyInstanceUid][instance.seriesInstanceUid];
        setIfEmpty(s.seriesInstanceUid, instance.seriesInstanceUid);
        setIfEmpty(s.modality, instance.modality);
        setIfEmpty(s.description, instance.seriesDescription);
        if (!s.seriesNumber)
            s.seriesNumber = instance.seriesNumber;
        s.instances.push_back(std::move(instance));
    }
    if (withoutSeriesUid > 0)
        warnings.push_back(
            std::to_string(withoutSeriesUid) +
            " instance(s) have no SeriesInstanceUID; they are grouped into one series");

    std::vector<PatientInfo> result;
    for (auto& [patientKey, patient] : patients) {
        for (auto& [studyUid, study] : studies[patientKey]) {
            for (auto& [seriesUid, s] : series[patientKey][studyUid]) {
                std::stable_sort(s.instances.begin(), s.instances.end(),
                                 [](const InstanceInfo& a, const InstanceInfo& b) {
                                     return std::tuple(optionalKey(a.instanceNumber), a.path) <
                                            std::tuple(optionalKey(b.instanceNumber), b.path);
                                 });
                study.series.push_back(std::move(s));
            }
            std::sort(study.series.begin(), study.series.end(),
                      [](const SeriesInfo& a, const SeriesInfo& b) {
                          return std::tuple(optionalKey(a.seriesNumber), a.seriesInstanceUid) <
                                 std::tuple(optionalKey(b.seriesNumber), b.seriesInstanceUid);
                      });
            patient.studies.push_back(std::move(study));
        }
        std::sort(patient.studies.begin(), patient.studies.end(),
                  [](const StudyInfo& a, const StudyInfo& b) {
                      return std::tie(a.date, a.time, a.studyInstanceUid) <
                             std::tie(b.date, b.time, b.studyInstanceUid);
                  });
        result.push_back(std::move(patient));
    }
    std::sort(result.begin(), result.end(), [](const PatientInfo& a, const PatientInfo& b) {
        return std::tie(a.name, a.patientId) < std::tie(b.name, b.patientId);
    });
    return result;
}

void finishIndex(DicomIndex& index, const std::vector<fs::path>& files, core::Progress* progress,
                 const core::ImportLimits& limits) {
    HeaderResults headers = readHeaders(files, progress, limits);
    index.filesExamined = files.size();
    for (auto& error : headers.errors)
        index.errors.push_back(std::move(error));
    for (const auto& dicomdir : headers.skippedDicomdirs)
        index.warnings.push_back("DICOMDIR " + dicomdir +
                                 " skipped: a folder scan reads the image files themselves");
    index.patients = groupInstances(std::move(headers.instances), index.warnings);
    // Errors sorted by file so output is the same on every run and machine.
    std::stable_sort(index.errors.begin(), index.errors.end(),
                     [](const FileError& a, const FileError& b) { return a.file < b.file; });
}

} // namespace lw::dicom::detail
