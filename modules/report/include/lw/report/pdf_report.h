#pragma once

// The PDF report (QPdfWriter, A4): page 1 the patient / study / series header (optionally
// anonymised) and the exported picture; from page 2 the annotations and measurements as a table
// (continued over further pages when long) and the free-text comment; every page carries the
// date, the software version and "page i of N".

#include "lw/annotation/annotation.h"
#include "lw/input/open_input.h"
#include "lw/render/camera.h"
#include "lw/render/silhouette_renderer.h"
#include "lw/render/visible_polylines.h"

#include <QByteArray>
#include <QColor>
#include <QDateTime>
#include <QImage>
#include <QString>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace lw::report {

struct ReportInfo {
    std::optional<input::DicomIdentity> identity; // none for volume files and phantoms
    std::string sourceDescription;                // OpenedVolume::description
    std::string method;     // how the picture was made: method, iso-value, view
    std::string comment;    // free text (UTF-8), wrapped
    bool anonymise = false; // patient name, ID, birth date, sex and accession left out
    QDateTime created = QDateTime::currentDateTime();
    std::string softwareVersion;
};

// How a picture was made, for ReportInfo::method and the Secondary Capture's derivation:
// "Linework silhouette method 3 (z-buffer silhouette, Morar et al. 2013), iso-value 400, view
// azimuth 30, elevation 10".
std::string describeRendering(render::SilhouetteMethod method, double iso,
                              const render::CameraSetup& view);

// The header's rows (label, value) as page 1 shows them.
std::vector<std::pair<QString, QString>> reportHeaderRows(const ReportInfo& info);

// Vector lines over the report's picture, in its pixels (pictureLines()).
struct PictureLines {
    std::vector<render::Polyline> lines;
    double width = 1.0;
    QColor colour = Qt::black;
    std::vector<render::Polyline> hidden; // under them, in the hidden style (strokeHiddenLines)
};

// The PDF's bytes. `picture` is the exported image with the annotations burned in; `lines`, when
// given, are drawn over it as vector paths (the silhouette, sharp at any zoom).
QByteArray renderPdfReport(const ReportInfo& info, const QImage& picture,
                           const std::vector<annotation::Annotation>& annotations,
                           const PictureLines& lines = {});

} // namespace lw::report
