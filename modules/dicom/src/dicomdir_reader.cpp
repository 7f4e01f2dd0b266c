#include "dicomdir_reader.h"

#include "instance_grouping.h"
#include "lw/core/error.h"
#include "scan_paths.h"

#include <algorithm>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcsequen.h>
#include <dcmtk/dcmdata/dcuid.h>

namespace fs = std::filesystem;

namespace lw::dicom::detail {

namespace {

// Nested DICOMDIRs (Philips: DICOMDIR -> DIRFILE -> DIRFILE) are rarely deeper than 3; the
// limit only stops pathological chains that the cycle guard cannot see (distinct copies).
constexpr int kMaxDicomdirDepth = 16;
constexpr const char* kMissingReason = "referenced by DICOMDIR but missing";

enum class Reference { None, Present, Missing, Nested, Rejected };

std::string getString(DcmItem& item, const DcmTagKey& key) {
    OFString value;
    if (item.findAndGetOFStringArray(key, value).good())
        return std::string(value.c_str());
    return {};
}

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
    const std::string classInFile = trimBlanks(getString(record, DCM_ReferencedSOPClassUIDInFile));
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

// Where the walk through one DICOMDIR's records stands: the PATIENT and STUDY records seen
// last give the context of a SERIES record.
struct RecordWalk {
    ListedSeries context;
    std::string currentSeries;
    bool sawPatient = false;
    bool sawStudy = false;
};

// PATIENT, STUDY and SERIES records: what they list, and whether this file's records come in
// the usual top-down order (only then is the context of a series without files trusted).
void noteHierarchy(DcmItem& record, RecordWalk& walk, DicomdirState& state) {
    const std::string type = trimBlanks(getString(record, DCM_DirectoryRecordType));
    if (type == "PATIENT") {
        walk.sawPatient = true;
        walk.sawStudy = false;
        walk.currentSeries.clear();
        walk.context.patientId = trimBlanks(getString(record, DCM_PatientID));
        walk.context.patientName = trimBlanks(getString(record, DCM_PatientName));
    } else if (type == "STUDY") {
        state.recordsInOrder = state.recordsInOrder && walk.sawPatient;
        walk.sawStudy = true;
        walk.currentSeries.clear();
        walk.context.studyInstanceUid = trimBlanks(getString(record, DCM_StudyInstanceUID));
        walk.context.studyId = trimBlanks(getString(record, DCM_StudyID));
        walk.context.studyDescription = trimBlanks(getString(record, DCM_StudyDescription));
        walk.context.studyDate = trimBlanks(getString(record, DCM_StudyDate));
        walk.context.studyTime = trimBlanks(getString(record, DCM_StudyTime));
        if (!walk.context.studyInstanceUid.empty())
            state.listedStudies.insert(walk.context.studyInstanceUid);
    } else if (type == "SERIES") {
        state.recordsInOrder = state.recordsInOrder && walk.sawStudy;
        walk.currentSeries = trimBlanks(getString(record, DCM_SeriesInstanceUID));
        if (!walk.currentSeries.empty()) {
            state.listedSeries.insert(walk.currentSeries);
            ListedSeries listed = walk.context;
            listed.modality = trimBlanks(getString(record, DCM_Modality));
            listed.description = trimBlanks(getString(record, DCM_SeriesDescription));
            Sint32 number = 0;
            if (record.findAndGetSint32(DCM_SeriesNumber, number).good())
                listed.seriesNumber = int(number);
            state.listedSeriesRecords.try_emplace(walk.currentSeries, std::move(listed));
        }
    }
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
    RecordWalk walk;
    const unsigned long count = loaded.usable;
    for (unsigned long i = 0; i < count; ++i) {
        DcmItem* record = records->getItem(i);
        if (record == nullptr)
            continue;
        Uint16 inUse = 0xFFFF;
        if (record->findAndGetUint16(DCM_RecordInUseFlag, inUse).good() && inUse == 0)
            continue; // deleted record (retired mechanism, still found on old media)
        noteHierarchy(*record, walk, state);
        const Reference reference = handleReference(*record, dicomdir, state, depth);
        if (!walk.currentSeries.empty() &&
            (reference == Reference::Present || reference == Reference::Missing)) {
            ListedSeries& listed = state.listedSeriesRecords[walk.currentSeries];
            ++listed.referenced;
            if (reference == Reference::Missing)
                ++listed.missing;
        }
    }
}

} // namespace

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

namespace {

// The patient a listed series without readable files goes under: found by ID, or added.
PatientInfo& patientOf(DicomIndex& index, const ListedSeries& listed) {
    auto patient =
        std::find_if(index.patients.begin(), index.patients.end(),
                     [&](const PatientInfo& p) { return p.patientId == listed.patientId; });
    if (patient != index.patients.end())
        return *patient;
    PatientInfo added;
    added.patientId = listed.patientId;
    added.name = listed.patientName;
    return index.patients.emplace_back(std::move(added));
}

StudyInfo& studyOf(PatientInfo& patient, const ListedSeries& listed) {
    auto study =
        std::find_if(patient.studies.begin(), patient.studies.end(), [&](const StudyInfo& s) {
            return s.studyInstanceUid == listed.studyInstanceUid;
        });
    if (study != patient.studies.end())
        return *study;
    StudyInfo added;
    added.studyInstanceUid = listed.studyInstanceUid;
    added.studyId = listed.studyId;
    added.description = listed.studyDescription;
    added.date = listed.studyDate;
    added.time = listed.studyTime;
    return patient.studies.emplace_back(std::move(added));
}

void noteReferencedCounts(DicomIndex& index, const std::string& uid, const ListedSeries& listed) {
    for (auto& patient : index.patients)
        for (auto& study : patient.studies)
            for (auto& series : study.series)
                if (series.seriesInstanceUid == uid) {
                    series.referencedFiles = listed.referenced;
                    series.missingFiles = listed.missing;
                }
}

// A series the DICOMDIR lists but none of whose files could be read: shown with its counts.
void addUnreadSeries(DicomIndex& index, const std::string& uid, const ListedSeries& listed) {
    StudyInfo& study = studyOf(patientOf(index, listed), listed);
    SeriesInfo series;
    series.seriesInstanceUid = uid;
    series.modality = listed.modality;
    series.description = listed.description;
    series.seriesNumber = listed.seriesNumber;
    series.referencedFiles = listed.referenced;
    series.missingFiles = listed.missing;
    const auto position =
        std::find_if(study.series.begin(), study.series.end(), [&](const SeriesInfo& s) {
            return std::tuple(optionalKey(series.seriesNumber), series.seriesInstanceUid) <
                   std::tuple(optionalKey(s.seriesNumber), s.seriesInstanceUid);
        });
    study.series.insert(position, std::move(series));
}

} // namespace

// Structured bindings are not captured by the lambdas below (clang 14 cannot): the entries are
// handed on by name.
void addListedSeries(DicomIndex& index, const DicomdirState& state) {
    for (const auto& entry : state.listedSeriesRecords) {
        const std::string& uid = entry.first;
        const ListedSeries& listed = entry.second;
        if (listed.referenced == 0)
            continue; // a series record without image records: nothing to say about it
        noteReferencedCounts(index, uid, listed);
        if (index.findSeries(uid) == nullptr && state.recordsInOrder)
            addUnreadSeries(index, uid, listed);
    }
}

} // namespace lw::dicom::detail
