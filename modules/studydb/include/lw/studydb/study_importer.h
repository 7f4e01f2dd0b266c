#pragma once

// Imports a DICOM folder, DICOMDIR or single file into the study database: scan the headers,
// plan the volumes of every series, make a thumbnail of each (the middle slice of its largest
// volume, windowed), then write everything in ONE transaction. Cancelled before or during the
// write, the database is exactly as it was.

#include "lw/core/progress.h"
#include "lw/studydb/study_database.h"
#include "lw/studydb/study_records.h"

#include <QImage>
#include <QString>
#include <memory>

namespace lw::dicom {
struct DicomIndex;
}
namespace lw::volume {
class Volume;
}

namespace lw::studydb {

// Thumbnails fit in a square of this many pixels, aspect (in mm) kept.
constexpr int kThumbnailSize = 128;

// Runs on the calling thread; opens its own connection to `databasePath` (so it may run on a
// worker thread while the UI holds another connection to the same file). `onProgress` gets the
// overall fraction and a message, possibly from several scanner threads at once (make it
// thread-safe); `cancel` may be set from any thread. Returns the summary
// (cancelled = true when it stopped, with nothing written). Throws core::Error when the input
// path cannot be read at all or the database cannot be opened or written.
ImportSummary importStudies(const QString& databasePath, const QString& inputPath,
                            core::Progress::Callback onProgress = {},
                            std::shared_ptr<const core::CancelToken> cancel = {});

// Builds the batch the importer would write (scan result in, records out); no database access.
// Exposed for tests and tools. Per-series decode failures become warnings, not exceptions.
ImportBatch buildImportBatch(const dicom::DicomIndex& index, core::Progress* progress = nullptr);

// An 8-bit greyscale thumbnail of slice z of `volume` (one-slice volumes: z = 0): CT is shown
// with the soft-tissue window W 400 / L 40 HU, anything else between its 1st and 99th
// percentile; scaled to fit `size`, aspect kept in mm.
QImage makeThumbnail(const volume::Volume& volume, bool isCt, int size = kThumbnailSize);

} // namespace lw::studydb
