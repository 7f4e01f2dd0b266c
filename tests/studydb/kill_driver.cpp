// The process lw_studydb_kill_tests kills (issue 10, "nothing lost"): what the workstation does
// when it imports and exports, in one program with nothing else around it.
//
//   lw_studydb_kill_driver DATABASE INPUT EXPORT_FOLDER
//
// Imports INPUT into the study database DATABASE (studydb::importStudies: one transaction), then
// exports the first series' thumbnail, scaled up so that encoding and writing take a while, as
// EXPORT_FOLDER/review.png and EXPORT_FOLDER/report.pdf (report::writeExportFile: atomic).
// Each phase is announced on stdout before it starts ("write database" when the importer
// starts its one transaction, "write png" / "write pdf" when the bytes are ready and the atomic
// write begins), so the test can kill inside the short windows that matter.
#include "lw/core/error.h"
#include "lw/report/export_files.h"
#include "lw/report/pdf_report.h"
#include "lw/studydb/study_database.h"
#include "lw/studydb/study_importer.h"

#include <QGuiApplication>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <random>

namespace {

void announce(const char* phase) {
    std::printf("%s\n", phase);
    std::fflush(stdout);
}

// The first series' thumbnail at `side` pixels with deterministic noise over it: every
// complete export of the same input has the same PNG bytes, and noise does not compress, so the
// PNG is megabytes and its write lasts long enough for kills to land inside it.
QImage exportPicture(const QString& databasePath, int side) {
    const lw::studydb::StudyDatabase database(databasePath);
    for (const auto& patient : database.patients())
        for (const auto& study : patient.studies)
            for (const auto& series : study.series)
                if (!series.thumbnail().isNull()) {
                    QImage picture =
                        series.thumbnail().scaled(side, side).convertToFormat(QImage::Format_RGB32);
                    std::mt19937 noise(1);
                    for (int y = 0; y < side; ++y) {
                        auto* row = reinterpret_cast<QRgb*>(picture.scanLine(y));
                        for (int x = 0; x < side; ++x)
                            row[x] ^= noise() & 0x3f3f3f;
                    }
                    return picture;
                }
    throw lw::core::Error(databasePath.toStdString(), "no series with a thumbnail was imported");
}

void exportBoth(const QImage& picture, const std::filesystem::path& folder) {
    announce("export png");
    const auto png = folder / "review.png";
    const QByteArray pngBytes = lw::report::encodePngBytes(picture, png);
    announce("write png");
    lw::report::writeExportFile(png, pngBytes, lw::core::Overwrite::Allow);
    announce("export pdf");
    lw::report::ReportInfo info;
    info.sourceDescription = "kill test";
    info.method = "thumbnail";
    info.created = QDateTime(QDate(2026, 11, 23), QTime(12, 0));
    const QByteArray pdfBytes = lw::report::renderPdfReport(info, picture, {});
    announce("write pdf");
    lw::report::writeExportFile(folder / "report.pdf", pdfBytes, lw::core::Overwrite::Allow);
}

// Announces the importer's last stage, its one database transaction, when it begins.
lw::core::Progress::Callback announceTheWrite() {
    auto announced = std::make_shared<std::atomic<bool>>(false);
    return [announced](double, const std::string& message) {
        if (message.find("study database") != std::string::npos && !announced->exchange(true))
            announce("write database");
    };
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
        lw::studydb::importStudies(database, QString::fromLocal8Bit(argv[2]), announceTheWrite());
        announce("thumbnail");
        exportBoth(exportPicture(database, 1600), std::filesystem::path(argv[3]));
        announce("done");
        return 0;
    } catch (const lw::core::Error& error) {
        std::fprintf(stderr, "%s\n", error.what());
        return 1;
    }
}
