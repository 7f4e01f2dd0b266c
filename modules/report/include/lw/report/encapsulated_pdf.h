#pragma once

// DICOM Encapsulated PDF (Encapsulated PDF Storage, 1.2.840.10008.5.1.4.1.1.104.1) of the PDF
// report: a new series (modality DOC) in the source's study (same StudyInstanceUID and patient
// module), so the report can be sent back to the PACS next to the CT it was made from and the
// Secondary Capture of the same review. DCMTK stays inside this module (PRIVATE).

#include "lw/core/file_util.h"
#include "lw/input/open_input.h"

#include <QByteArray>
#include <QDateTime>
#include <filesystem>
#include <string>

namespace lw::report {

struct EncapsulatedPdfSeries {
    input::DicomIdentity source; // patient and study repeated, series replaced
    std::string documentTitle = "Linework report";
    std::string seriesDescription = "Linework report";
    std::string softwareVersion;
    QDateTime created = QDateTime::currentDateTime(); // Content Date/Time
};

// The Part 10 file's bytes: the PDF as the Encapsulated Document (its length in
// EncapsulatedDocumentLength; a pad byte 0 after an odd length), BurnedInAnnotation YES (the
// report names the patient), series number source + 1001 (the Secondary Capture's + 1).
// Throws core::Error naming `subject` when the source has no StudyInstanceUID, the PDF is empty
// or does not start with "%PDF-", or a value does not fit its attribute.
std::vector<char> encapsulatedPdfBytes(const QByteArray& pdf, const EncapsulatedPdfSeries& series,
                                       const std::string& subject);

// Writes encapsulatedPdfBytes() to `path` atomically (report::writeExportFile's rules: an
// existing file only with Overwrite::Allow, never through a link). Throws core::Error naming
// the file and the reason.
void writeEncapsulatedPdf(const std::filesystem::path& path, const QByteArray& pdf,
                          const EncapsulatedPdfSeries& series, core::Overwrite overwrite);

} // namespace lw::report
