#pragma once

// The inputs every fuzz target feeds to Linework, one function per reader. Each writes the bytes
// to a file (the readers take paths, as users give them) and runs the reader the way an import
// does; core::Error is the expected answer to a bad file and is swallowed, anything else (a
// crash, a sanitizer finding, another exception type) is a finding. The libFuzzer mains
// (fuzz_main.cpp) and the regression test over tests/data/fuzz (fuzz_regression_test.cpp) both
// call these, so a finding's input replays in every build, with or without clang.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string_view>

namespace lw::fuzz {

using Bytes = std::span<const std::uint8_t>;

// One DICOM file: scanned as a one-file import, every series planned and loaded, and every
// frame of the instance decoded on its own.
void importDicomFile(Bytes data);
// A DICOMDIR at the root of a file-set; fileSetRoot holds the files it may reference.
void importDicomdir(Bytes data, const std::filesystem::path& fileSetRoot);
void readNrrdFile(Bytes data);
void readNiftiFile(Bytes data);
void readPvmFile(Bytes data);

// The reader named `target` ("dicom_file", "dicomdir", "nrrd", "nifti", "pvm"); false for an
// unknown name. The DICOMDIR reader gets `fileSetRoot`.
bool runTarget(std::string_view target, Bytes data, const std::filesystem::path& fileSetRoot);

// The file-set a fuzzed DICOMDIR sits in, made once per process under scratchFolder(): a copy
// of the shared data's tiny DICOMDIR tree (its own DICOMDIR left out) when `sharedData` has it,
// so the seeds' references resolve to real files; an empty folder otherwise.
const std::filesystem::path& fileSetRoot(const std::filesystem::path& sharedData);

// A folder of this process for the files the readers are given (removed by the OS's tmp
// cleaning, not by us: libFuzzer may end the process at any point).
const std::filesystem::path& scratchFolder();

} // namespace lw::fuzz
