#include "dicom_test_writer.h"

#include <cstdint>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcrleerg.h>
#include <dcmtk/dcmdata/dcrlerp.h>
#include <dcmtk/dcmdata/dcuid.h>
#include <dcmtk/dcmjpeg/djencode.h>
#include <dcmtk/dcmjpeg/djrplol.h>
#include <dcmtk/dcmjpls/djencode.h>
#include <dcmtk/dcmjpls/djrparam.h>
#include <dlfcn.h>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <zlib.h>

namespace lw::dicom::test {

namespace {

// The encoders are registered once per process; DCMTK's codec list is global.
struct EncoderRegistration {
    EncoderRegistration() {
        DJEncoderRegistration::registerCodecs();
        // Raw (not "cooked") JPEG-LS encoding: the cooked path goes through DicomImage and
        // crashes in DCMTK 3.6.7 on small signed images; raw keeps the stored bits exactly.
        DJLSEncoderRegistration::registerCodecs(0, 0, 0, 0, OFFalse);
        DcmRLEEncoderRegistration::registerCodecs();
    }
    ~EncoderRegistration() {
        DcmRLEEncoderRegistration::cleanup();
        DJLSEncoderRegistration::cleanup();
        DJEncoderRegistration::cleanup();
    }
};

void ensureEncoders() { static EncoderRegistration registration; }

void check(const OFCondition& status, const std::string& what) {
    if (status.bad())
        throw std::runtime_error("test DICOM writer: " + what + ": " + status.text());
}

std::string formatDouble(double value) {
    std::ostringstream out;
    out.precision(10);
    out << value;
    return out.str();
}

template <typename Seq> std::string joinNumbers(const Seq& values) {
    std::string text;
    for (const double v : values) {
        if (!text.empty())
            text += '\\';
        text += formatDouble(v);
    }
    return text;
}

// DCMTK's JPEG-LS encoder calls JpegLsEncode, which the system CharLS 2 also exports with
// another ABI; when that copy was loaded first the encoder crashes. Link the test with
// DCMTK::dcmjpls first and --no-as-needed (see tests/dicom/CMakeLists.txt) to get DCMTK's.
bool dcmtkCharlsIsBound() {
    void* symbol = dlsym(RTLD_DEFAULT, "JpegLsEncode");
    Dl_info info{};
    if (!symbol || !dladdr(symbol, &info) || !info.dli_fname)
        return true;
    return std::string(info.dli_fname).find("dcmtkcharls") != std::string::npos;
}

E_TransferSyntax toXfer(TestTransferSyntax syntax) {
    switch (syntax) {
    case TestTransferSyntax::ExplicitLittle: return EXS_LittleEndianExplicit;
    case TestTransferSyntax::ImplicitLittle: return EXS_LittleEndianImplicit;
    case TestTransferSyntax::ExplicitBig: return EXS_BigEndianExplicit;
    case TestTransferSyntax::Deflated: return EXS_DeflatedLittleEndianExplicit;
    case TestTransferSyntax::JpegLossless: return EXS_JPEGProcess14SV1;
    case TestTransferSyntax::JpegLsLossless: return EXS_JPEGLSLossless;
    case TestTransferSyntax::Rle: return EXS_RLELossless;
    }
    return EXS_LittleEndianExplicit;
}

} // namespace

std::string transferSyntaxUid(TestTransferSyntax syntax) { return DcmXfer(toXfer(syntax)).getXferID(); }

std::string makeTestUid() {
    char buffer[100];
    dcmGenerateUniqueIdentifier(buffer, SITE_INSTANCE_UID_ROOT);
    return buffer;
}

std::vector<int> rampPixels(int rows, int columns, int start, int step) {
    std::vector<int> values(std::size_t(rows) * std::size_t(columns));
    for (std::size_t i = 0; i < values.size(); ++i)
        values[i] = start + int(i) * step;
    return values;
}

namespace {
// The slice's pixels as PixelData in its BitsAllocated (8 or 16), native.
void putPixelData(DcmDataset& ds, const TestSlice& s) {
    const std::size_t count = std::size_t(s.rows) * std::size_t(s.columns) * std::size_t(s.numberOfFrames);
    if (!s.pixels.empty() && s.pixels.size() != count)
        throw std::runtime_error("test DICOM writer: pixel count does not match rows*columns*frames");
    if (s.bitsAllocated == 8) {
        std::vector<Uint8> bytes(count, 0);
        for (std::size_t i = 0; i < s.pixels.size(); ++i)
            bytes[i] = Uint8(s.pixels[i] & 0xFF);
        // An odd number of bytes is padded to even length by DCMTK when written.
        check(ds.putAndInsertUint8Array(DCM_PixelData, bytes.data(), unsigned(count)), "PixelData");
    } else if (s.bitsAllocated == 16) {
        std::vector<Uint16> words(count, 0);
        for (std::size_t i = 0; i < s.pixels.size(); ++i)
            words[i] = Uint16(std::uint32_t(s.pixels[i]) & 0xFFFFu);
        check(ds.putAndInsertUint16Array(DCM_PixelData, words.data(), unsigned(count)), "PixelData");
    } else {
        throw std::runtime_error("test DICOM writer: BitsAllocated must be 8 or 16");
    }
}

// An encapsulated transfer syntax: the native PixelData re-encoded by DCMTK's codecs.
void encodePixelData(DcmDataset& ds, const TestSlice& s, E_TransferSyntax xfer) {
    if (DcmXfer(xfer).isEncapsulated()) {
        std::unique_ptr<DcmRepresentationParameter> params;
        if (s.transferSyntax == TestTransferSyntax::JpegLossless)
            params = std::make_unique<DJ_RPLossless>(1, 0);
        else if (s.transferSyntax == TestTransferSyntax::JpegLsLossless && !dcmtkCharlsIsBound())
            throw std::runtime_error("test DICOM writer: JpegLsEncode resolves to the system CharLS, not DCMTK's; "
                                     "link DCMTK::dcmjpls first with --no-as-needed");
        else if (s.transferSyntax == TestTransferSyntax::JpegLsLossless)
            params = std::make_unique<DJLSRepresentationParameter>(2, OFTrue);
        else
            params = std::make_unique<DcmRLERepresentationParameter>();
        check(ds.chooseRepresentation(xfer, params.get()), "encode " + transferSyntaxUid(s.transferSyntax));
        if (!ds.canWriteXfer(xfer))
            throw std::runtime_error("test DICOM writer: DCMTK could not encode " + transferSyntaxUid(s.transferSyntax));
    }
}
} // namespace

void writeTestSlice(const std::filesystem::path& path, const TestSlice& s) {
    ensureEncoders();
    DcmFileFormat file;
    DcmDataset* ds = file.getDataset();
    auto put = [&](const DcmTagKey& key, const std::string& value) {
        check(ds->putAndInsertString(key, value.c_str()), "put " + DcmTag(key).toString().substr(0));
    };
    put(DCM_SOPClassUID, s.sopClassUid);
    put(DCM_SOPInstanceUID, s.sopInstanceUid.empty() ? makeTestUid() : s.sopInstanceUid);
    put(DCM_StudyInstanceUID, s.studyUid.empty() ? makeTestUid() : s.studyUid);
    put(DCM_SeriesInstanceUID, s.seriesUid.empty() ? makeTestUid() : s.seriesUid);
    put(DCM_Modality, s.modality);
    put(DCM_PatientID, s.patientId);
    put(DCM_PatientName, s.patientName);
    put(DCM_SeriesDescription, s.seriesDescription);
    put(DCM_ImageType, s.imageType);
    if (s.seriesNumber)
        put(DCM_SeriesNumber, std::to_string(*s.seriesNumber));
    if (s.instanceNumber)
        put(DCM_InstanceNumber, std::to_string(*s.instanceNumber));
    if (s.acquisitionNumber)
        put(DCM_AcquisitionNumber, std::to_string(*s.acquisitionNumber));
    if (s.position)
        put(DCM_ImagePositionPatient, joinNumbers(std::array<double, 3>{s.position->x, s.position->y, s.position->z}));
    if (s.orientation)
        put(DCM_ImageOrientationPatient, joinNumbers(*s.orientation));
    if (s.pixelSpacing)
        put(DCM_PixelSpacing, joinNumbers(std::array<double, 2>{s.pixelSpacing->x, s.pixelSpacing->y}));
    put(DCM_SliceThickness, formatDouble(s.sliceThickness));
    if (s.rescaleSlope)
        put(DCM_RescaleSlope, formatDouble(*s.rescaleSlope));
    if (s.rescaleIntercept)
        put(DCM_RescaleIntercept, formatDouble(*s.rescaleIntercept));

    check(ds->putAndInsertUint16(DCM_SamplesPerPixel, 1), "SamplesPerPixel");
    put(DCM_PhotometricInterpretation, s.photometric);
    check(ds->putAndInsertUint16(DCM_Rows, Uint16(s.rows)), "Rows");
    check(ds->putAndInsertUint16(DCM_Columns, Uint16(s.columns)), "Columns");
    check(ds->putAndInsertUint16(DCM_BitsAllocated, Uint16(s.bitsAllocated)), "BitsAllocated");
    check(ds->putAndInsertUint16(DCM_BitsStored, Uint16(s.bitsStored)), "BitsStored");
    check(ds->putAndInsertUint16(DCM_HighBit, Uint16(s.highBit)), "HighBit");
    check(ds->putAndInsertUint16(DCM_PixelRepresentation, Uint16(s.pixelRepresentation)), "PixelRepresentation");
    if (s.numberOfFrames > 1)
        put(DCM_NumberOfFrames, std::to_string(s.numberOfFrames));

    if (s.writePixelData)
        putPixelData(*ds, s);
    const E_TransferSyntax xfer = toXfer(s.transferSyntax);
    encodePixelData(*ds, s, xfer);
    check(file.saveFile(OFFilename(path.c_str()), xfer), "save " + path.string());
}

namespace {

void appendLe(std::string& out, std::uint64_t value, int bytes) {
    for (int i = 0; i < bytes; ++i)
        out.push_back(char((value >> (8 * i)) & 0xff));
}

// One explicit VR little endian element (OB in the long form).
void appendElement(std::string& out, std::uint16_t group, std::uint16_t element, const char* vr,
                   std::string value) {
    if (value.size() % 2)
        value.push_back(std::string(vr) == "UI" ? '\0' : ' ');
    appendLe(out, group, 2);
    appendLe(out, element, 2);
    out.append(vr, 2);
    if (std::string(vr) == "OB") { // long form: 2 reserved bytes, 4-byte length
        appendLe(out, 0, 2);
        appendLe(out, value.size(), 4);
    } else {
        appendLe(out, value.size(), 2);
    }
    out += value;
}

void appendUs(std::string& out, std::uint16_t group, std::uint16_t element, int value) {
    std::string bytes;
    appendLe(bytes, std::uint64_t(value), 2);
    appendElement(out, group, element, "US", bytes);
}

} // namespace

namespace {

// Writes `prefix` as is, then `data` followed by `zeros` zero bytes, raw-deflated when `deflated`.
void writeDataSet(std::ofstream& file, const std::string& prefix, const std::string& data,
                  std::size_t zeros, bool deflated) {
    file.write(prefix.data(), std::streamsize(prefix.size()));
    if (!deflated) {
        file.write(data.data(), std::streamsize(data.size()));
        const std::string chunk(1 << 20, '\0');
        for (std::size_t left = zeros; left > 0;) {
            const std::size_t n = std::min(left, chunk.size());
            file.write(chunk.data(), std::streamsize(n));
            left -= n;
        }
        return;
    }
    z_stream z{};
    if (deflateInit2(&z, 1, Z_DEFLATED, -MAX_WBITS, 8, Z_DEFAULT_STRATEGY) != Z_OK)
        throw std::runtime_error("deflateInit2 failed");
    std::string out(1 << 16, '\0');
    auto pump = [&](const char* in, std::size_t size, int flush) {
        z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in));
        z.avail_in = uInt(size);
        do {
            z.next_out = reinterpret_cast<Bytef*>(out.data());
            z.avail_out = uInt(out.size());
            deflate(&z, flush);
            file.write(out.data(), std::streamsize(out.size() - z.avail_out));
        } while (z.avail_out == 0 || z.avail_in > 0);
    };
    pump(data.data(), data.size(), Z_NO_FLUSH);
    const std::string chunk(1 << 20, '\0');
    for (std::size_t left = zeros; left > 0;) {
        const std::size_t n = std::min(left, chunk.size());
        pump(chunk.data(), n, Z_NO_FLUSH);
        left -= n;
    }
    pump(nullptr, 0, Z_FINISH);
    deflateEnd(&z);
}

} // namespace

void writeHandMadeImage(const std::filesystem::path& path, const HandMadeImage& image) {
    std::string meta;
    appendElement(meta, 0x0002, 0x0001, "OB", std::string("\0\1", 2));
    appendElement(meta, 0x0002, 0x0002, "UI", "1.2.840.10008.5.1.4.1.1.2");
    appendElement(meta, 0x0002, 0x0003, "UI", "1.2.826.0.1.3680043.2.1143.99.1");
    appendElement(meta, 0x0002, 0x0010, "UI",
                  image.deflate ? "1.2.840.10008.1.2.1.99" : "1.2.840.10008.1.2.1");
    std::string head(128, '\0');
    head += "DICM";
    std::string groupLength;
    appendLe(groupLength, meta.size(), 4);
    appendElement(head, 0x0002, 0x0000, "UL", groupLength);
    head += meta;
    std::string out;
    appendElement(out, 0x0008, 0x0016, "UI", "1.2.840.10008.5.1.4.1.1.2");
    appendElement(out, 0x0008, 0x0018, "UI", "1.2.826.0.1.3680043.2.1143.99.1");
    appendElement(out, 0x0008, 0x0060, "CS", "CT");
    appendElement(out, 0x0020, 0x000D, "UI", "1.2.826.0.1.3680043.2.1143.99.2");
    appendElement(out, 0x0020, 0x000E, "UI", "1.2.826.0.1.3680043.2.1143.99.3");
    appendUs(out, 0x0028, 0x0002, 1);
    appendElement(out, 0x0028, 0x0004, "CS", "MONOCHROME2");
    if (!image.numberOfFrames.empty())
        appendElement(out, 0x0028, 0x0008, "IS", image.numberOfFrames);
    appendUs(out, 0x0028, 0x0010, image.rows);
    appendUs(out, 0x0028, 0x0011, image.columns);
    appendUs(out, 0x0028, 0x0100, image.bitsAllocated);
    appendUs(out, 0x0028, 0x0101, image.bitsAllocated);
    appendUs(out, 0x0028, 0x0102, image.bitsAllocated - 1);
    appendUs(out, 0x0028, 0x0103, 1);
    if (image.privateBytesBeforePixels > 0 || image.declaredPrivateLength) {
        appendElement(out, 0x0029, 0x0010, "LO", "LINEWORK TEST");
        appendLe(out, 0x0029, 2);
        appendLe(out, 0x1000, 2);
        out.append(image.privateVr, 0, 2);
        appendLe(out, 0, 2);
        appendLe(
            out,
            image.declaredPrivateLength.value_or(std::uint32_t(image.privateBytesBeforePixels)), 4);
        out.append(image.privateBytesBeforePixels, '\0');
    }
    std::size_t zeros = 0;
    if (image.writePixelData) {
        appendLe(out, 0x7FE0, 2);
        appendLe(out, 0x0010, 2);
        out += image.bitsAllocated == 8 ? "OB" : "OW";
        appendLe(out, 0, 2);
        appendLe(out, image.declaredPixelDataLength.value_or(std::uint32_t(image.pixelDataBytes)),
                 4);
        zeros = image.pixelDataBytes;
    }
    std::ofstream file(path, std::ios::binary | std::ios::trunc);
    writeDataSet(file, head, out, zeros, image.deflate);
    if (!file)
        throw std::runtime_error("cannot write " + path.string());
}

} // namespace lw::dicom::test
