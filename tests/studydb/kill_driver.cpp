// The process lw_studydb_kill_tests kills (issue 10, "nothing lost"): what the workstation does
// when it imports and exports, in one program with nothing else around it.
//
//   lw_studydb_kill_driver DATABASE INPUT EXPORT_FOLDER
//
// Imports INPUT into the study database DATABASE (studydb::importStudies: one transaction), then
// exports the first series' thumbnail, scaled up so that encoding and writing take a while, as
// EXPORT_FOLDER/review.png and EXPORT_FOLDER/report.pdf (report::writeExportFile: atomic).
// Each phase is announced on stdout before it starts, so the test knows where a kill landed.
#include "lw/core/error.h"
#include "lw/report/export_files.h"
#include "lw/report/pdf_report.h"
#include "lw/studydb/study_database.h"
#include "lw/studydb/study_importer.h"

#include <QGuiApplication>
#include <cstdio>
#include <filesystem>

namespace {

void announce(const char* phase) {
    std::printf("%s\n", phase);
    std::fflush(stdout);
}

// The first series' thumbnail at `side` pixels: deterministic, so every complete export of the
// same input has the same PNG bytes.
QImage firstThumbnail(const QString& databasePath, int side) {
    const lw::studydb::StudyDatabase database(databasePath);
    for (const auto& patient : database.patients())
        for (const auto& study : patient.studies)
            for (const auto& series : study.series)
                if (!series.thumbnail().isNull())
                    return series.thumbnail()
                        .scaled(side, side)
                        .convertToFormat(QImage::Format_RGB32);
    throw lw::core::Error(databasePath.toStdString(), "no series with a thumbnail was imported");
}

void exportBoth(const QImage& picture, const std::filesystem::path& folder) {
    announce("export png");
    const auto png = folder / "review.png";
    lw::report::writeExportFile(png, lw::report::encodePngBytes(picture, png),
                                lw::core::Overwrite::Allow);
    announce("export pdf");
    lw::report::ReportInfo info;
    info.sourceDescription = "kill test";
    info.method = "thumbnail";
    info.created = QDateTime(QDate(2026, 11, 23), QTime(12, 0));
    lw::report::writeExportFile(folder / "report.pdf",
                                lw::report::renderPdfReport(info, picture, {}),
                                lw::core::Overwrite::Allow);
}

} // namespace

int main(int argc, char** argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: %s DATABASE INPUT EXPORT_FOLDER\n", argv[0]);
        return 2;
    }
    int qtArgc = 3;
    char name[] = "lw_studydb_kill_driver", platform[] = "-platform", offscreen[] = "offscreen";
    char* qtArgv[] = {name, platform, offscreen, nullptr};
    const QGuiApplication application(qtArgc, qtArgv);
    try {
        announce("import");
        const QString database = QString::fromLocal8Bit(argv[1]);
        lw::studydb::importStudies(database, QString::fromLocal8Bit(argv[2]));
        announce("thumbnail");
        exportBoth(firstThumbnail(database, 2400), std::filesystem::path(argv[3]));
        announce("done");
        return 0;
    } catch (const lw::core::Error& error) {
        std::fprintf(stderr, "%s\n", error.what());
        return 1;
    }
}
