#pragma once

// What the report's DICOM writers (Secondary Capture, Encapsulated PDF) share: new UIDs, string
// attributes that name themselves when refused, the Patient and General Study modules copied
// from the source so a new series joins its study, and the Part 10 file's bytes. Private to
// lw_report: DCMTK stays inside this module.

#include "lw/input/open_input.h"

#include <QDateTime>
#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdatset.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <string>
#include <vector>

namespace lw::report::detail {

// A new UID under DCMTK's root for `root` (SITE_SERIES_UID_ROOT, SITE_INSTANCE_UID_ROOT).
std::string newUid(const char* root);

bool isAscii(const std::string& text);

// Puts a string attribute; a DCMTK refusal (a value its VR cannot hold) throws core::Error
// naming `subject` and the attribute.
void put(DcmDataset& dataset, const DcmTagKey& tag, const std::string& value,
         const std::string& subject);

// SpecificCharacterSet ISO_IR 192 (UTF-8) when any of `texts` is not plain ASCII.
void putCharacterSet(DcmDataset& dataset, const std::vector<std::string>& texts,
                     const std::string& subject);

// Patient and General Study modules: repeated from the source so the series joins its study.
void putPatientAndStudy(DcmDataset& dataset, const input::DicomIdentity& source,
                        const std::string& subject);

// The General Equipment attributes and the SC Equipment module (conversion type: workstation).
void putEquipment(DcmDataset& dataset, const std::string& softwareVersion,
                  const std::string& subject);

// DICOM's DA and TM of `when`.
std::string dicomDate(const QDateTime& when);
std::string dicomTime(const QDateTime& when);

// The Part 10 file's bytes (preamble, meta header, explicit VR little endian data set);
// `payloadBytes` sizes the buffer (the pixels or the document it carries).
std::vector<char> encodeFile(DcmFileFormat& file, std::size_t payloadBytes,
                             const std::string& subject);

} // namespace lw::report::detail
