#pragma once

// Internal to lw::dicom: the module boundary. DCMTK, GDCM and the standard library throw their
// own exception types (std::out_of_range from a damaged DICOMDIR, std::bad_alloc, ...); the
// public API promises core::Error naming the file, so every public entry funnels through here.

#include "lw/core/error.h"

#include <exception>
#include <new>
#include <string>
#include <utility>

namespace lw::dicom::detail {

// Runs `work` and turns anything that is neither core::Error nor core::Cancelled into
// core::Error(subject, reason). Cancellation passes through untouched: it is not a failure.
template <typename Work> auto atModuleBoundary(const std::string& subject, Work&& work) {
    try {
        return std::forward<Work>(work)();
    } catch (const core::Error&) {
        throw;
    } catch (const core::Cancelled&) {
        throw;
    } catch (const std::bad_alloc&) {
        throw core::Error(subject, "out of memory");
    } catch (const std::exception& error) {
        throw core::Error(subject, std::string("unexpected failure: ") + error.what());
    } catch (...) {
        throw core::Error(subject, "unexpected failure of unknown type");
    }
}

} // namespace lw::dicom::detail
