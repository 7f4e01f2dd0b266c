#include "lw/report/encapsulated_pdf.h"

#include "dicom_dataset.h"
#include "lw/core/error.h"
#include "lw/report/export_files.h"

#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcuid.h>

namespace lw::report {
namespace {

using detail::put;

// Encapsulated Document Series, General Equipment and SC Equipment, Encapsulated Document and
// SOP Common modules (the Patient and General Study ones come from the source).
void putSeriesAndDocument(DcmDataset& dataset, const EncapsulatedPdfSeries& series,
                          const std::string& subject) {
    const std::string date = detail::dicomDate(series.created);
    const std::string time = detail::dicomTime(series.created);
    put(dataset, DCM_SOPClassUID, UID_EncapsulatedPDFStorage, subject);
    put(dataset, DCM_SOPInstanceUID, detail::newUid(SITE_INSTANCE_UID_ROOT), subject);
    put(dataset, DCM_InstanceCreationDate, date, subject);
    put(dataset, DCM_InstanceCreationTime, time, subject);
    put(dataset, DCM_Modality, "DOC", subject);
    put(dataset, DCM_SeriesInstanceUID, detail::newUid(SITE_SERIES_UID_ROOT), subject);
    put(dataset, DCM_SeriesNumber, std::to_string(series.source.seriesNumber.value_or(0) + 1001),
        subject);
    put(dataset, DCM_SeriesDescription, series.seriesDescription, subject);
    detail::putEquipment(dataset, series.softwareVersion, subject);
    put(dataset, DCM_InstanceNumber, "1", subject);
    put(dataset, DCM_ContentDate, date, subject);
    put(dataset, DCM_ContentTime, time, subject);
    put(dataset, DCM_AcquisitionDateTime, "", subject); // type 2: the report was not acquired
    put(dataset, DCM_BurnedInAnnotation, "YES", subject);
    put(dataset, DCM_DocumentTitle, series.documentTitle, subject);
    // Type 2: no coded document kind is claimed, so the sequence is present and empty.
    dataset.insertEmptyElement(DCM_ConceptNameCodeSequence);
    put(dataset, DCM_MIMETypeOfEncapsulatedDocument, "application/pdf", subject);
}

void putDocument(DcmDataset& dataset, const QByteArray& pdf, const std::string& subject) {
    // The length before the pad byte that keeps the value's length even.
    const OFCondition length =
        dataset.putAndInsertUint32(DCM_EncapsulatedDocumentLength, Uint32(pdf.size()));
    QByteArray padded = pdf;
    if (padded.size() % 2)
        padded.append('\0');
    const OFCondition document = dataset.putAndInsertUint8Array(
        DCM_EncapsulatedDocument, reinterpret_cast<const Uint8*>(padded.constData()),
        static_cast<unsigned long>(padded.size()));
    if (length.bad() || document.bad())
        throw core::Error(subject, std::string("cannot store the PDF: ") +
                                       (document.bad() ? document : length).text());
}

} // namespace

std::vector<char> encapsulatedPdfBytes(const QByteArray& pdf, const EncapsulatedPdfSeries& series,
                                       const std::string& subject) {
    if (series.source.studyInstanceUid.empty())
        throw core::Error(subject, "an Encapsulated PDF joins the source's study, but the input "
                                   "is not DICOM (no StudyInstanceUID)");
    if (!pdf.startsWith("%PDF-"))
        throw core::Error(subject, "the report to encapsulate is not a PDF");
    if (quint64(pdf.size()) >= 0xFFFFFFF0u)
        throw core::Error(subject, "the PDF is too large for one DICOM value (4 GiB)");
    DcmFileFormat file;
    DcmDataset& dataset = *file.getDataset();
    const input::DicomIdentity& source = series.source;
    detail::putCharacterSet(
        dataset, {source.patientName, source.studyDescription, series.documentTitle}, subject);
    detail::putPatientAndStudy(dataset, source, subject);
    putSeriesAndDocument(dataset, series, subject);
    putDocument(dataset, pdf, subject);
    return detail::encodeFile(file, std::size_t(pdf.size()), subject);
}

void writeEncapsulatedPdf(const std::filesystem::path& path, const QByteArray& pdf,
                          const EncapsulatedPdfSeries& series, core::Overwrite overwrite) {
    core::checkWritableTarget(path, overwrite);
    const std::vector<char> bytes = encapsulatedPdfBytes(pdf, series, path.string());
    writeExportFile(path, QByteArray(bytes.data(), qsizetype(bytes.size())), overwrite);
}

} // namespace lw::report
