#pragma once

// Exporting a review from the workstation through modules/report: both panels (or one) rendered
// again at the chosen size rather than scaled, the annotations burned in through the same camera,
// written as a PNG, a PDF report or a DICOM Secondary Capture series. Rendering and writing run
// off the UI thread wherever the panels' own GL contexts are not needed, behind a progress dialog
// when they take longer than a moment. Every file is written atomically (nothing half-written
// is ever left); an existing file is replaced only with Overwrite::Allow, which the caller
// passes after the user agreed. Each function returns an empty string, or the reason naming
// the file (or folder) and what went wrong.

#include "lw/core/file_util.h"
#include "lw/report/export_image.h"

#include <QSize>
#include <QString>

class QWidget;

namespace lw::gui {

class ReviewWidget;

// The picture of an export.
struct ExportPicture {
    QSize panelSize; // of each panel, in pixels
    report::PanelLayout layout = report::PanelLayout::SideBySide;
};

struct ReportOptions {
    ExportPicture picture;
    QString comment;        // free text under the measurements
    bool anonymise = false; // patient name, ID, birth date, sex and accession left out
};

QString exportReviewPng(ReviewWidget& review, const QString& path, const ExportPicture& picture,
                        core::Overwrite overwrite = core::Overwrite::Refuse,
                        QWidget* progressParent = nullptr);

// The A4 report: header, the picture, the annotations and measurements, the comment.
QString exportReviewReport(ReviewWidget& review, const QString& path, const ReportOptions& options,
                           core::Overwrite overwrite = core::Overwrite::Refuse,
                           QWidget* progressParent = nullptr);

// The picture as a new series of the source's study in `folder` (LWSC0001.dcm), ready to send
// to the PACS; the review must be of a DICOM series.
QString exportReviewSecondaryCapture(ReviewWidget& review, const QString& folder,
                                     const ExportPicture& picture,
                                     core::Overwrite overwrite = core::Overwrite::Refuse,
                                     QWidget* progressParent = nullptr);

// What Send to PACS stores, from one rendering of the panels: the picture as a Secondary
// Capture in `secondaryCaptureFolder` and the A4 report as DICOM Encapsulated PDF at
// `encapsulatedPdfPath`, both new series of the source's study (neither target may exist).
QString exportReviewForPacs(ReviewWidget& review, const QString& secondaryCaptureFolder,
                            const QString& encapsulatedPdfPath, const ReportOptions& options,
                            QWidget* progressParent = nullptr);

} // namespace lw::gui
