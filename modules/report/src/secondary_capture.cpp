#include "lw/report/secondary_capture.h"

#include "dicom_dataset.h"
#include "lw/core/error.h"

#include <QDateTime>
#include <cstdio>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcuid.h>
#include <vector>

namespace lw::report {
namespace {

using detail::newUid;
using detail::put;

struct InstanceIds {
    std::string seriesUid;
    int seriesNumber = 0;
    int instanceNumber = 1;
    QDateTime created;
};

// General Series, SC Equipment, General Image, SC Image and SOP Common modules.
void putSeriesAndImage(DcmDataset& dataset, const SecondaryCaptureSeries& series,
                       const InstanceIds& ids, const std::string& subject) {
    const std::string date = detail::dicomDate(ids.created);
    const std::string time = detail::dicomTime(ids.created);
    put(dataset, DCM_SOPClassUID, UID_SecondaryCaptureImageStorage, subject);
    put(dataset, DCM_SOPInstanceUID, newUid(SITE_INSTANCE_UID_ROOT), subject);
    put(dataset, DCM_InstanceCreationDate, date, subject);
    put(dataset, DCM_InstanceCreationTime, time, subject);
    put(dataset, DCM_Modality, "OT", subject); // derived pictures, not CT values
    put(dataset, DCM_SeriesInstanceUID, ids.seriesUid, subject);
    put(dataset, DCM_SeriesNumber, std::to_string(ids.seriesNumber), subject);
    put(dataset, DCM_SeriesDescription, series.seriesDescription, subject);
    // Type 2C, required for paired body parts; a picture of the review has no side of its own
    // (dciodvfy cannot tell the condition and wants it present, empty is its "unknown").
    put(dataset, DCM_Laterality, "", subject);
    detail::putEquipment(dataset, series.softwareVersion, subject);
    put(dataset, DCM_InstanceNumber, std::to_string(ids.instanceNumber), subject);
    put(dataset, DCM_PatientOrientation, "", subject);
    put(dataset, DCM_ContentDate, date, subject);
    put(dataset, DCM_ContentTime, time, subject);
    put(dataset, DCM_ImageType, "DERIVED\\SECONDARY", subject);
    put(dataset, DCM_DerivationDescription, series.derivationDescription, subject);
    put(dataset, DCM_BurnedInAnnotation, "YES", subject);
    put(dataset, DCM_DateOfSecondaryCapture, date, subject);
    put(dataset, DCM_TimeOfSecondaryCapture, time, subject);
}

void putPixels(DcmDataset& dataset, const QImage& picture, const std::string& subject) {
    const QImage rgb = picture.convertToFormat(QImage::Format_RGB888);
    std::vector<Uint8> pixels(std::size_t(rgb.width()) * std::size_t(rgb.height()) * 3);
    for (int y = 0; y < rgb.height(); ++y)
        std::copy_n(rgb.constScanLine(y), std::size_t(rgb.width()) * 3,
                    pixels.data() + std::size_t(y) * std::size_t(rgb.width()) * 3);
    dataset.putAndInsertUint16(DCM_SamplesPerPixel, 3);
    put(dataset, DCM_PhotometricInterpretation, "RGB", subject);
    dataset.putAndInsertUint16(DCM_PlanarConfiguration, 0);
    dataset.putAndInsertUint16(DCM_Rows, Uint16(rgb.height()));
    dataset.putAndInsertUint16(DCM_Columns, Uint16(rgb.width()));
    dataset.putAndInsertUint16(DCM_BitsAllocated, 8);
    dataset.putAndInsertUint16(DCM_BitsStored, 8);
    dataset.putAndInsertUint16(DCM_HighBit, 7);
    dataset.putAndInsertUint16(DCM_PixelRepresentation, 0);
    const OFCondition status = dataset.putAndInsertUint8Array(
        DCM_PixelData, pixels.data(), static_cast<unsigned long>(pixels.size()));
    if (status.bad())
        throw core::Error(subject, std::string("cannot store the pixel data: ") + status.text());
}

std::vector<char> secondaryCaptureFile(const QImage& picture, const SecondaryCaptureSeries& series,
                                       const InstanceIds& ids, const std::string& subject) {
    if (picture.width() > 65535 || picture.height() > 65535 || picture.isNull())
        throw core::Error(subject, "a Secondary Capture holds 1 to 65535 pixels per side");
    DcmFileFormat file;
    DcmDataset& dataset = *file.getDataset();
    const input::DicomIdentity& source = series.source;
    detail::putCharacterSet(
        dataset, {source.patientName, source.studyDescription, series.derivationDescription},
        subject);
    detail::putPatientAndStudy(dataset, source, subject);
    putSeriesAndImage(dataset, series, ids, subject);
    putPixels(dataset, picture, subject);
    return detail::encodeFile(
        file, std::size_t(picture.width()) * std::size_t(picture.height()) * 3, subject);
}

} // namespace

std::string secondaryCaptureFileName(int number) {
    char name[32];
    std::snprintf(name, sizeof name, "LWSC%04d.dcm", number);
    return name;
}

void checkSecondaryCaptureTarget(const std::filesystem::path& folder, core::Overwrite overwrite) {
    std::error_code ec;
    if (std::filesystem::is_directory(folder, ec))
        core::checkWritableTarget(core::fileInFolder(folder, secondaryCaptureFileName(1)),
                                  overwrite);
    else // created when written; "out/" names the folder "out" just as "out" does
        core::checkWritableTarget(folder.has_filename() ? folder : folder.parent_path(),
                                  core::Overwrite::Refuse);
}

std::vector<std::filesystem::path> writeSecondaryCapture(const std::filesystem::path& folder,
                                                         const std::vector<QImage>& pictures,
                                                         const SecondaryCaptureSeries& series,
                                                         core::Overwrite overwrite) {
    if (series.source.studyInstanceUid.empty())
        throw core::Error(folder.string(), "a Secondary Capture joins the source's study, but "
                                           "the input is not DICOM (no StudyInstanceUID)");
    std::error_code ec;
    const bool created = std::filesystem::create_directory(folder, ec);
    if (ec)
        throw core::Error(folder.string(), "cannot create the folder: " + ec.message());
    InstanceIds ids;
    ids.seriesUid = newUid(SITE_SERIES_UID_ROOT);
    ids.seriesNumber = series.source.seriesNumber.value_or(0) + 1000;
    ids.created = QDateTime::currentDateTime();
    std::vector<std::filesystem::path> written;
    try {
        for (std::size_t i = 0; i < pictures.size(); ++i) {
            ids.instanceNumber = int(i) + 1;
            const std::filesystem::path path =
                core::fileInFolder(folder, secondaryCaptureFileName(ids.instanceNumber));
            core::checkWritableTarget(path, overwrite);
            const std::vector<char> bytes =
                secondaryCaptureFile(pictures[i], series, ids, path.string());
            core::writeFileAtomically(path, bytes.data(), bytes.size(), overwrite);
            written.push_back(path);
        }
    } catch (...) {
        for (const std::filesystem::path& path : written)
            std::filesystem::remove(path, ec);
        if (created)
            std::filesystem::remove(folder, ec);
        throw;
    }
    return written;
}

} // namespace lw::report
