#include "lw/dicom/dicom_scanner.h"

#include "dicom_boundary.h"
#include "dicom_file.h"
#include "lw/core/error.h"
#include "lw/core/log.h"
#include "lw/core/parallel.h"

#include <algorithm>
#include <cctype>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcsequen.h>
#include <dcmtk/dcmdata/dcuid.h>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <tuple>
#include <unordered_map>

namespace fs = std::filesystem;

namespace lw::dicom {
namespace {

const core::LogCategory kLog("lw.dicom");

// Nested DICOMDIRs (Philips: DICOMDIR -> DIRFILE -> DIRFILE) are rarely deeper than 3; the
// limit only stops pathological chains that the cycle guard cannot see (distinct copies).
constexpr int kMaxDicomdirDepth = 16;
constexpr const char* kMissingReason = "referenced by DICOMDIR but missing";

std::string lower(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return text;
}

bool isNamedDicomdir(const fs::path& path) {
    return lower(path.filename().string()) == "dicomdir";
}

// Canonical where possible so that the same folder reached twice (symlinks) is recognised.
fs::path canonicalOrAbsolute(const fs::path& path) {
    std::error_code ec;
    fs::path result = fs::canonical(path, ec);
    if (ec)
        result = fs::absolute(path, ec).lexically_normal();
    return result;
}

// isDicomdirFile opens the file; on the error paths of a scan any failure means "no".
bool safeIsDicomdir(const fs::path& path) noexcept {
    try {
        return isDicomdirFile(path);
    } catch (...) {
        return false;
    }
}

bool isInside(const fs::path& child, const fs::path& root) {
    const auto rel = child.lexically_relative(root);
    if (rel.empty())
        return false;
    const auto first = rel.begin()->string();
    return first != ".." && !rel.is_absolute();
}

// ---- folder walk ---------------------------------------------------------------------------

struct WalkState {
    std::vector<fs::path> files;
    std::vector<FileError> errors;
    std::set<fs::path> visitedDirs; // canonical: guards against symlink loops
    core::Progress* progress = nullptr;
};

void walkFolder(const fs::path& dir, WalkState& state) {
    if (!state.visitedDirs.insert(canonicalOrAbsolute(dir)).second)
        return;
    if (state.progress)
        state.progress->throwIfCancelled();
    std::error_code ec;
    fs::directory_iterator it(dir, fs::directory_options::skip_permission_denied, ec);
    if (ec) {
        state.errors.push_back({dir.string(), "cannot list folder: " + ec.message()});
        return;
    }
    std::vector<fs::path> subdirs;
    for (; it != fs::directory_iterator(); it.increment(ec)) {
        if (ec)
            break;
        const fs::path entry = it->path();
        std::error_code statEc;
        const auto status = fs::status(entry, statEc); // follows symlinks
        if (statEc) {
            // A dangling symlink is a file someone expected to be there: say so.
            state.errors.push_back({entry.string(), "cannot access: " + statEc.message()});
            continue;
        }
        if (fs::is_directory(status))
            subdirs.push_back(entry);
        else if (fs::is_regular_file(status))
            state.files.push_back(entry);
    }
    if (ec)
        state.errors.push_back({dir.string(), "error while listing folder: " + ec.message()});
    std::sort(subdirs.begin(), subdirs.end());
    for (const auto& sub : subdirs)
        walkFolder(sub, state);
}

// ---- DICOMDIR ------------------------------------------------------------------------------

// Resolves ReferencedFileID components below `base`, exact case first and then
// case-insensitively: CD exports write upper-case IDs, but copies to case-sensitive file
// systems often end up lower case (or the other way round).
class CaseInsensitiveResolver {
public:
    std::optional<fs::path> resolve(const fs::path& base,
                                    const std::vector<std::string>& components) {
        fs::path current = base;
        for (const auto& component : components) {
            fs::path candidate = current / component;
            std::error_code ec;
            if (fs::exists(candidate, ec)) {
                current = std::move(candidate);
                continue;
            }
            const auto& listing = listFolder(current);
            const auto found = listing.find(lower(component));
            if (found == listing.end())
                return std::nullopt;
            current = current / found->second;
        }
        std::error_code ec;
        if (!fs::is_regular_file(current, ec))
            return std::nullopt;
        return current;
    }

private:
    const std::map<std::string, std::string>& listFolder(const fs::path& folder) {
        auto [it, inserted] = m_listings.try_emplace(folder.string());
        if (inserted) {
            std::error_code ec;
            std::vector<std::string> names;
            for (fs::directory_iterator d(folder, ec), end; !ec && d != end; d.increment(ec))
                names.push_back(d->path().filename().string());
            // Sorted so that two names differing only in case resolve the same way every run.
            std::sort(names.begin(), names.end());
            for (const auto& name : names)
                it->second.try_emplace(lower(name), name);
        }
        return it->second;
    }

    std::unordered_map<std::string, std::map<std::string, std::string>> m_listings;
};

struct ListedSeries {
    std::string patientId, patientName;
    std::string studyInstanceUid, studyId, studyDescription, studyDate, studyTime;
    std::string modality, description;
    std::optional<int> seriesNumber;
    std::size_t referenced = 0;
    std::size_t missing = 0;
};

enum class Reference { None, Present, Missing, Nested, Rejected };

struct DicomdirState {
    fs::path root;          // the file-set root: the folder of the DICOMDIR the scan started at
    fs::path canonicalRoot; // for the containment check after symlinks are resolved
    std::set<fs::path> visitedDicomdirs;
    std::set<fs::path> seenFiles;
    std::vector<fs::path> files;
    std::vector<FileError> errors;
    std::vector<std::string> warnings;
    std::set<std::string> listedSeries;
    std::set<std::string> listedStudies;
    // What the SERIES records say, with the PATIENT and STUDY records before them, so series
    // whose files are all missing still appear in the index (a CD with a series held back).
    std::map<std::string, ListedSeries> listedSeriesRecords;
    bool recordsInOrder = true; // every file's records run PATIENT, STUDY, SERIES, IMAGE...
    CaseInsensitiveResolver resolver;
    core::Progress* progress = nullptr;
};

template <typename T> std::tuple<bool, T> optionalKey(const std::optional<T>& value) {
    return {!value.has_value(), value.value_or(T{})};
}

std::string getString(DcmItem& item, const DcmTagKey& key) {
    OFString value;
    if (item.findAndGetOFStringArray(key, value).good())
        return std::string(value.c_str());
    return {};
}

std::string trim(std::string text) {
    const auto first = text.find_first_not_of(" \t\r\n");
    if (first == std::string::npos)
        return {};
    const auto last = text.find_last_not_of(" \t\r\n");
    return text.substr(first, last - first + 1);
}

// Splits a ReferencedFileID ("DIR\SUB\FILE") into components; nullopt when the ID would leave
// the file-set root (absolute, drive letter, "..") or is malformed.
std::optional<std::vector<std::string>> splitFileId(const std::string& id) {
    std::vector<std::string> components;
    if (id.empty() || id.front() == '\\' || id.front() == '/')
        return std::nullopt;
    std::string current;
    auto flush = [&]() -> bool {
        const std::string component = trim(current);
        current.clear();
        if (component.empty() || component == "." || component == ".." ||
            component.find(':') != std::string::npos)
            return false;
        components.push_back(component);
        return true;
    };
    for (char c : id) {
        if (c == '\\' || c == '/') {
            if (!flush())
                return std::nullopt;
        } else {
            current += c;
        }
    }
    if (!flush())
        return std::nullopt;
    return components;
}

void walkDicomdir(const fs::path& dicomdir, DicomdirState& state, int depth, bool topLevel);

Reference handleReference(DcmItem& record, const fs::path& dicomdir, DicomdirState& state,
                          int depth) {
    const std::string id = getString(record, DCM_ReferencedFileID);
    if (id.empty())
        return Reference::None;
    const auto components = splitFileId(id);
    if (!components) {
        state.errors.push_back({(dicomdir.parent_path() / id).string(),
                                "ReferencedFileID '" + id + "' in " + dicomdir.string() +
                                    " leaves the file-set root " + state.root.string()});
        return Reference::Rejected;
    }
    fs::path lexical = state.root;
    for (const auto& c : *components)
        lexical /= c;

    // IDs are relative to the file-set root. Some writers (nested DIRFILEs) make them relative
    // to the nested directory file's own folder instead; try that second.
    auto resolved = state.resolver.resolve(state.root, *components);
    if (!resolved && dicomdir.parent_path() != state.root)
        resolved = state.resolver.resolve(dicomdir.parent_path(), *components);
    if (!resolved) {
        if (state.seenFiles.insert(lexical.lexically_normal()).second)
            state.errors.push_back({lexical.string(), kMissingReason});
        return Reference::Missing;
    }
    if (!isInside(canonicalOrAbsolute(*resolved), state.canonicalRoot)) {
        state.errors.push_back(
            {resolved->string(), "referenced by " + dicomdir.string() +
                                     " but resolves (through a link) outside the file-set root " +
                                     state.root.string()});
        return Reference::Rejected;
    }
    const std::string classInFile = trim(getString(record, DCM_ReferencedSOPClassUIDInFile));
    const bool nested = classInFile == UID_MediaStorageDirectoryStorage ||
                        (classInFile.empty() && safeIsDicomdir(*resolved));
    if (nested) {
        walkDicomdir(*resolved, state, depth + 1, false);
        return Reference::Nested;
    }
    if (state.seenFiles.insert(resolved->lexically_normal()).second)
        state.files.push_back(*resolved);
    return Reference::Present;
}

// The directory records of one DICOMDIR as far as they could be parsed.
struct DicomdirRecords {
    DcmSequenceOfItems* records = nullptr; // owned by the DcmFileFormat passed in
    unsigned long usable = 0;              // the records before any damage
    std::string damage;                    // why parsing stopped early; empty when it did not
};

// Loads a DICOMDIR. A parse that fails part-way (a file cut short, a broken item) keeps the
// records read before the damage: DCMTK leaves them in the data set with a bad status. The
// record the parse stopped in is the last one of the sequence and is left out, since its values
// may be cut short. (A library exception from the parse is walkDicomdir's: see there.)
DicomdirRecords loadDicomdirRecords(const fs::path& dicomdir, DcmFileFormat& file) {
    DicomdirRecords result;
    // Read-only: loadFile never writes. ERM_autoDetect accepts files without meta header.
    const OFCondition status = file.loadFile(OFFilename(dicomdir.c_str()), EXS_Unknown,
                                             EGL_noChange, DCM_MaxReadLength, ERM_autoDetect);
    if (status.bad())
        result.damage = std::string("cannot read DICOMDIR: ") + status.text();
    DcmDataset* dataset = file.getDataset();
    if (dataset == nullptr ||
        dataset->findAndGetSequence(DCM_DirectoryRecordSequence, result.records).bad() ||
        result.records == nullptr)
        return result;
    result.usable = result.records->card();
    if (!result.damage.empty() && result.usable > 0)
        --result.usable;
    return result;
}

// Reads one DICOMDIR file and follows its records; walkDicomdir wraps it.
void walkDicomdirRecords(const fs::path& dicomdir, DicomdirState& state, int depth, bool topLevel) {
    if (state.progress)
        state.progress->throwIfCancelled();
    if (!state.visitedDicomdirs.insert(canonicalOrAbsolute(dicomdir)).second) {
        state.warnings.push_back("DICOMDIR " + dicomdir.string() +
                                 " is referenced more than once (cycle); followed once");
        return;
    }
    if (depth > kMaxDicomdirDepth) {
        state.errors.push_back({dicomdir.string(), "DICOMDIRs nested too deeply; not followed"});
        return;
    }
    DcmFileFormat file;
    const DicomdirRecords loaded = loadDicomdirRecords(dicomdir, file);
    if (!loaded.damage.empty()) {
        // Nothing before the damage: for the top-level DICOMDIR the scan has nothing to show.
        if (loaded.usable == 0 && topLevel)
            throw core::Error(dicomdir.string(), loaded.damage);
        state.errors.push_back(
            {dicomdir.string(), loaded.usable == 0
                                    ? loaded.damage
                                    : loaded.damage + "; the " + std::to_string(loaded.usable) +
                                          " records before the damage are used"});
    }
    if (loaded.usable == 0) {
        if (loaded.damage.empty())
            state.warnings.push_back("DICOMDIR " + dicomdir.string() + " has no directory records");
        return;
    }
    DcmSequenceOfItems* records = loaded.records;
    // The records are walked as a flat list rather than through the offset links: the offsets
    // are often absent, stale after copying, or the records reordered, while every record that
    // matters carries its ReferencedFileID. The hierarchy comes from the image headers.
    // The order of the records gives the context of a SERIES record (the PATIENT and STUDY
    // before it); it is used only for series without any readable file, and only when this
    // file's records come in the usual top-down order.
    ListedSeries context;
    std::string currentSeries;
    bool sawPatient = false, sawStudy = false;
    const unsigned long count = loaded.usable;
    for (unsigned long i = 0; i < count; ++i) {
        DcmItem* record = records->getItem(i);
        if (record == nullptr)
            continue;
        Uint16 inUse = 0xFFFF;
        if (record->findAndGetUint16(DCM_RecordInUseFlag, inUse).good() && inUse == 0)
            continue; // deleted record (retired mechanism, still found on old media)
        const std::string type = trim(getString(*record, DCM_DirectoryRecordType));
        if (type == "PATIENT") {
            sawPatient = true;
            sawStudy = false;
            currentSeries.clear();
            context.patientId = trim(getString(*record, DCM_PatientID));
            context.patientName = trim(getString(*record, DCM_PatientName));
        } else if (type == "STUDY") {
            state.recordsInOrder = state.recordsInOrder && sawPatient;
            sawStudy = true;
            currentSeries.clear();
            context.studyInstanceUid = trim(getString(*record, DCM_StudyInstanceUID));
            context.studyId = trim(getString(*record, DCM_StudyID));
            context.studyDescription = trim(getString(*record, DCM_StudyDescription));
            context.studyDate = trim(getString(*record, DCM_StudyDate));
            context.studyTime = trim(getString(*record, DCM_StudyTime));
            if (!context.studyInstanceUid.empty())
                state.listedStudies.insert(context.studyInstanceUid);
        } else if (type == "SERIES") {
            state.recordsInOrder = state.recordsInOrder && sawStudy;
            currentSeries = trim(getString(*record, DCM_SeriesInstanceUID));
            if (!currentSeries.empty()) {
                state.listedSeries.insert(currentSeries);
                ListedSeries listed = context;
                listed.modality = trim(getString(*record, DCM_Modality));
                listed.description = trim(getString(*record, DCM_SeriesDescription));
                Sint32 number = 0;
                if (record->findAndGetSint32(DCM_SeriesNumber, number).good())
                    listed.seriesNumber = int(number);
                state.listedSeriesRecords.try_emplace(currentSeries, std::move(listed));
            }
        }
        const Reference reference = handleReference(*record, dicomdir, state, depth);
        if (!currentSeries.empty() &&
            (reference == Reference::Present || reference == Reference::Missing)) {
            ListedSeries& listed = state.listedSeriesRecords[currentSeries];
            ++listed.referenced;
            if (reference == Reference::Missing)
                ++listed.missing;
        }
    }
}

// Adds the series a DICOMDIR lists but whose files are all missing, as empty series under their
// study and patient, and records how many referenced files each listed series lacks.
void addListedSeries(DicomIndex& index, const DicomdirState& state) {
    for (const auto& [uid, listed] : state.listedSeriesRecords) {
        if (listed.referenced == 0)
            continue; // a series record without image records: nothing to say about it
        for (auto& patient : index.patients)
            for (auto& study : patient.studies)
                for (auto& series : study.series)
                    if (series.seriesInstanceUid == uid) {
                        series.referencedFiles = listed.referenced;
                        series.missingFiles = listed.missing;
                    }
        if (index.findSeries(uid) != nullptr || !state.recordsInOrder)
            continue;
        auto patient =
            std::find_if(index.patients.begin(), index.patients.end(),
                         [&](const PatientInfo& p) { return p.patientId == listed.patientId; });
        if (patient == index.patients.end()) {
            PatientInfo added;
            added.patientId = listed.patientId;
            added.name = listed.patientName;
            index.patients.push_back(std::move(added));
            patient = index.patients.end() - 1;
        }
        auto study =
            std::find_if(patient->studies.begin(), patient->studies.end(), [&](const StudyInfo& s) {
                return s.studyInstanceUid == listed.studyInstanceUid;
            });
        if (study == patient->studies.end()) {
            StudyInfo added;
            added.studyInstanceUid = listed.studyInstanceUid;
            added.studyId = listed.studyId;
            added.description = listed.studyDescription;
            added.date = listed.studyDate;
            added.time = listed.studyTime;
            patient->studies.push_back(std::move(added));
            study = patient->studies.end() - 1;
        }
        SeriesInfo series;
        series.seriesInstanceUid = uid;
        series.modality = listed.modality;
        series.description = listed.description;
        series.seriesNumber = listed.seriesNumber;
        series.referencedFiles = listed.referenced;
        series.missingFiles = listed.missing;
        const auto position =
            std::find_if(study->series.begin(), study->series.end(), [&](const SeriesInfo& s) {
                return std::tuple(optionalKey(series.seriesNumber), series.seriesInstanceUid) <
                       std::tuple(optionalKey(s.seriesNumber), s.seriesInstanceUid);
            });
        study->series.insert(position, std::move(series));
    }
}

// ---- headers and grouping ------------------------------------------------------------------

struct HeaderResults {
    std::vector<InstanceInfo> instances;
    std::vector<FileError> errors;
    std::vector<std::string> skippedDicomdirs;
};

// A damaged DICOMDIR (an element length pointing past its value) makes DCMTK throw standard
// exceptions (std::out_of_range) from inside its parser; they become this file's error. The
// records parsed before such an exception cannot be kept: DCMTK attaches the record sequence to
// the data set only once it is read whole, so a throw inside it leaves none of them reachable.
// The top-level DICOMDIR is the whole input: it fails the scan.
void walkDicomdir(const fs::path& dicomdir, DicomdirState& state, int depth, bool topLevel) {
    std::string reason;
    try {
        walkDicomdirRecords(dicomdir, state, depth, topLevel);
        return;
    } catch (const core::Error&) {
        throw;
    } catch (const core::Cancelled&) {
        throw;
    } catch (const std::bad_alloc&) {
        reason = "out of memory while reading the DICOMDIR";
    } catch (const std::exception& error) {
        reason = std::string("damaged DICOMDIR: ") + error.what();
    } catch (...) {
        reason = "damaged DICOMDIR (unknown failure)";
    }
    if (topLevel)
        throw core::Error(dicomdir.string(), reason);
    state.errors.push_back({dicomdir.string(), reason});
}

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

// Optional numbers sort before "missing" so that numbered series come first.

void setIfEmpty(std::string& target, const std::string& value) {
    if (target.empty())
        target = value;
}

std::vector<PatientInfo> groupInstances(std::vector<InstanceInfo> instances,
                                        std::vector<std::string>& warnings) {
    // Deterministic input order first: the parallel read and the walk order must not leak out.
    std::sort(instances.begin(), instances.end(),
              [](const InstanceInfo& a, const InstanceInfo& b) { return a.path < b.path; });

    // The same object twice (copied folders, a file and its re-encoded twin): keep the first.
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

bool hasDicmMagic(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    char buffer[132] = {};
    if (!in.read(buffer, sizeof buffer))
        return false;
    return std::string_view(buffer + 128, 4) == "DICM";
}

DicomIndex scanDicomdir(const fs::path& dicomdir, core::Progress* progress,
                        const core::ImportLimits& limits) {
    DicomIndex index;
    index.fromDicomdir = true;
    DicomdirState state;
    state.root = dicomdir.parent_path().empty() ? fs::path(".") : dicomdir.parent_path();
    state.canonicalRoot = canonicalOrAbsolute(state.root);
    state.progress = progress;
    index.root = state.root;
    walkDicomdir(dicomdir, state, 0, true);

    index.errors = std::move(state.errors);
    index.warnings = std::move(state.warnings);
    std::sort(state.files.begin(), state.files.end());
    finishIndex(index, state.files, progress, limits);

    std::size_t seriesWithoutFiles = 0;
    for (const auto& uid : state.listedSeries) {
        const SeriesInfo* series = index.findSeries(uid);
        if (series == nullptr || series->instances.empty())
            ++seriesWithoutFiles;
    }
    addListedSeries(index, state);
    if (seriesWithoutFiles > 0)
        index.warnings.push_back("DICOMDIR lists " + std::to_string(state.listedSeries.size()) +
                                 " series; " + std::to_string(seriesWithoutFiles) +
                                 " of them have no readable file");
    kLog.info("DICOMDIR " + dicomdir.string() + ": " + std::to_string(index.instanceCount()) +
              " instances in " + std::to_string(index.seriesCount()) + " series, " +
              std::to_string(index.errors.size()) + " file errors");
    return index;
}

} // namespace

std::size_t DicomIndex::seriesCount() const {
    std::size_t count = 0;
    for (const auto& patient : patients)
        for (const auto& study : patient.studies)
            count += study.series.size();
    return count;
}

std::size_t DicomIndex::instanceCount() const {
    std::size_t count = 0;
    for (const auto* series : allSeries())
        count += series->instances.size();
    return count;
}

const SeriesInfo* DicomIndex::findSeries(std::string_view seriesInstanceUid) const {
    for (const auto* series : allSeries())
        if (series->seriesInstanceUid == seriesInstanceUid)
            return series;
    return nullptr;
}

std::vector<const SeriesInfo*> DicomIndex::allSeries() const {
    std::vector<const SeriesInfo*> result;
    for (const auto& patient : patients)
        for (const auto& study : patient.studies)
            for (const auto& series : study.series)
                result.push_back(&series);
    return result;
}

static DicomIndex scanDicomUnguarded(const fs::path& path, core::Progress* progress,
                                     const core::ImportLimits& limits) {
    std::error_code ec;
    const auto status = fs::status(path, ec);
    if (ec || !fs::exists(status))
        throw core::Error(path.string(), "does not exist");

    if (fs::is_directory(status)) {
        WalkState walk;
        walk.progress = progress;
        walkFolder(path, walk);
        std::sort(walk.files.begin(), walk.files.end());
        DicomIndex index;
        index.root = path;
        index.errors = std::move(walk.errors);
        finishIndex(index, walk.files, progress, limits);
        kLog.info("scanned " + path.string() + ": " + std::to_string(index.filesExamined) +
                  " files, " + std::to_string(index.instanceCount()) + " instances in " +
                  std::to_string(index.seriesCount()) + " series, " +
                  std::to_string(index.errors.size()) + " file errors");
        return index;
    }
    if (!fs::is_regular_file(status))
        throw core::Error(path.string(), "is neither a folder nor a regular file");

    // A file named DICOMDIR is parsed as one even without a meta header saying so.
    if (isNamedDicomdir(path) || safeIsDicomdir(path))
        return scanDicomdir(path, progress, limits);

    // A single file: it is the whole input, so failing to read it fails the scan.
    DicomIndex index;
    index.root = path.parent_path();
    index.filesExamined = 1;
    if (progress)
        progress->setTotal(1, "Reading DICOM header");
    InstanceInfo instance = readInstanceHeader(path, limits);
    if (instance.path.empty())
        instance.path = path.string();
    if (progress)
        progress->step();
    std::vector<InstanceInfo> one;
    one.push_back(std::move(instance));
    index.patients = groupInstances(std::move(one), index.warnings);
    return index;
}

static DicomIndex scanDicomFilesUnguarded(const std::vector<fs::path>& files,
                                          core::Progress* progress,
                                          const core::ImportLimits& limits) {
    DicomIndex index;
    if (!files.empty())
        index.root = files.front().parent_path();
    std::vector<fs::path> present;
    present.reserve(files.size());
    for (const fs::path& file : files) {
        std::error_code ec;
        const fs::file_status status = fs::status(file, ec);
        if (fs::is_regular_file(status))
            present.push_back(file);
        else if (!fs::exists(status))
            index.errors.push_back({file.string(), "file is missing"});
        else
            index.errors.push_back({file.string(), ec ? ec.message() : "not a regular file"});
    }
    // Sorted like a folder scan, so the grouping does not depend on the caller's order.
    std::sort(present.begin(), present.end());
    finishIndex(index, present, progress,
                limits); // adds the read errors and sorts all errors by file
    index.filesExamined = files.size();
    return index;
}

static bool looksLikeDicomInputUnguarded(const fs::path& path) {
    std::error_code ec;
    if (fs::is_directory(path, ec))
        return true;
    if (!fs::is_regular_file(path, ec))
        return false;
    if (isNamedDicomdir(path) || hasDicmMagic(path))
        return true;
    // Files without preamble (ACR-NEMA, stripped meta) or gzip-wrapped ones are recognised by
    // their usual suffixes; volume formats have their own suffixes, so these never clash.
    const std::string name = lower(path.filename().string());
    for (const char* suffix : {".dcm", ".dcm.gz", ".dicom", ".ima"})
        if (name.size() > std::string_view(suffix).size() && name.ends_with(suffix))
            return true;
    return false;
}

// The public entries: nothing but core::Error (naming the input) and core::Cancelled leaves them.
DicomIndex scanDicom(const fs::path& path, core::Progress* progress,
                     const core::ImportLimits& limits) {
    return detail::atModuleBoundary(path.string(),
                                    [&] { return scanDicomUnguarded(path, progress, limits); });
}

DicomIndex scanDicomFiles(const std::vector<fs::path>& files, core::Progress* progress,
                          const core::ImportLimits& limits) {
    const std::string subject =
        files.empty() ? std::string("DICOM file list") : files.front().parent_path().string();
    return detail::atModuleBoundary(
        subject, [&] { return scanDicomFilesUnguarded(files, progress, limits); });
}

bool looksLikeDicomInput(const fs::path& path) {
    return detail::atModuleBoundary(path.string(),
                                    [&] { return looksLikeDicomInputUnguarded(path); });
}

} // namespace lw::dicom
