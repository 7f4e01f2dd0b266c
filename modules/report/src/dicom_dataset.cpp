#include "dicom_dataset.h"

#include "lw/core/error.h"

#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcostrmb.h>
#include <dcmtk/dcmdata/dcuid.h>

namespace lw::report::detail {

std::string newUid(const char* root) {
    char buffer[100];
    dcmGenerateUniqueIdentifier(buffer, root);
    return buffer;
}

bool isAscii(const std::string& text) {
    for (const unsigned char c : text)
        if (c >= 0x80)
            return false;
    return true;
}

void put(DcmDataset& dataset, const DcmTagKey& tag, const std::string& value,
         const std::string& subject) {
    const OFCondition status = dataset.putAndInsertString(tag, value.c_str());
    if (status.bad())
        throw core::Error(subject, "cannot set " + std::string(DcmTag(tag).getTagName()) + " to '" +
                                       value + "': " + status.text());
}

void putCharacterSet(DcmDataset& dataset, const std::vector<std::string>& texts,
                     const std::string& subject) {
    for (const std::string& text : texts)
        if (!isAscii(text)) {
            put(dataset, DCM_SpecificCharacterSet, "ISO_IR 192", subject);
            return;
        }
}

void putPatientAndStudy(DcmDataset& dataset, const input::DicomIdentity& source,
                        const std::string& subject) {
    put(dataset, DCM_PatientName, source.patientName, subject);
    put(dataset, DCM_PatientID, source.patientId, subject);
    put(dataset, DCM_PatientBirthDate, source.patientBirthDate, subject);
    put(dataset, DCM_PatientSex, source.patientSex, subject);
    put(dataset, DCM_StudyInstanceUID, source.studyInstanceUid, subject);
    put(dataset, DCM_StudyDate, source.studyDate, subject);
    put(dataset, DCM_StudyTime, source.studyTime, subject);
    put(dataset, DCM_ReferringPhysicianName, "", subject);
    put(dataset, DCM_StudyID, source.studyId, subject);
    put(dataset, DCM_AccessionNumber, source.accessionNumber, subject);
    if (!source.studyDescription.empty())
        put(dataset, DCM_StudyDescription, source.studyDescription, subject);
}

void putEquipment(DcmDataset& dataset, const std::string& softwareVersion,
                  const std::string& subject) {
    put(dataset, DCM_ConversionType, "WSD", subject); // workstation
    put(dataset, DCM_Manufacturer, "Linework", subject);
    put(dataset, DCM_SoftwareVersions, softwareVersion, subject);
}

std::string dicomDate(const QDateTime& when) {
    return when.toString("yyyyMMdd").toStdString();
}

std::string dicomTime(const QDateTime& when) {
    return when.toString("HHmmss").toStdString();
}

std::vector<char> encodeFile(DcmFileFormat& file, std::size_t payloadBytes,
                             const std::string& subject) {
    std::vector<char> buffer(payloadBytes + (1 << 16));
    DcmOutputBufferStream stream(buffer.data(), offile_off_t(buffer.size()));
    file.transferInit();
    const OFCondition status =
        file.write(stream, EXS_LittleEndianExplicit, EET_ExplicitLength, nullptr);
    file.transferEnd();
    if (status.bad())
        throw core::Error(subject, std::string("DICOM encoding failed: ") + status.text());
    void* data = nullptr;
    offile_off_t length = 0;
    stream.flushBuffer(data, length);
    buffer.resize(std::size_t(length));
    return buffer;
}

} // namespace lw::report::detail
