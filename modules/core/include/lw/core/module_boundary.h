#pragma once

// The boundary of a module that reads what users bring (lw::dicom, lw::volume's readers): the
// libraries below it (DCMTK, OpenJPEG, zlib) and the standard library throw their own exception
// types (std::out_of_range from a damaged DICOMDIR, std::bad_alloc, filesystem_error, ...); the
// public API promises core::Error naming the file, so every public entry funnels through here.

#include "lw/core/error.h"

#include <exception>
#include <new>
#include <string>
#include <utility>

namespace lw::core {

// Runs `work` and turns anything that is neither Error nor Cancelled into Error(subject,
// reason). Cancellation passes through untouched: it is not a failure.
template <typename Work> auto atModuleBoundary(const std::string& subject, Work&& work) {
    try {
        return std::forward<Work>(work)();
    } catch (const Error&) {
        throw;
    } catch (const Cancelled&) {
        throw;
    } catch (const std::bad_alloc&) {
        throw Error(subject, "out of memory");
    } catch (const std::exception& error) {
        throw Error(subject, std::string("unexpected failure: ") + error.what());
    } catch (...) {
        throw Error(subject, "unexpected failure of unknown type");
    }
}

} // namespace lw::core
