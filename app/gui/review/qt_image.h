#pragma once

// The image conversions live in modules/report, which the CLI's export shares.
#include "lw/report/qt_image.h"

namespace lw::gui {
using report::toCoreImage;
using report::toQImage;
} // namespace lw::gui
