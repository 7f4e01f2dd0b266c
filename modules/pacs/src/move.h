#pragma once

// C-MOVE to the workstation's own storage SCP: the C-MOVE request goes out on the retrieve's
// association while the same DCMTK network accepts the PACS's associations and receives their
// C-STOREs (DIMSE_moveUser's sub-operation callback), into the same managed store as C-GET.
#include "association.h"
#include "transfer.h"

#include <dcmtk/dcmdata/dcdatset.h>

namespace lw::pacs::detail {

PresentationContext moveContext();

// One C-MOVE of `keys` to `destinationAet` (the workstation's AE title). Throws PacsError when
// the exchange breaks; a final failure status (the PACS cannot reach or does not know the
// destination) becomes the transfer's message.
void moveInstances(Association& association, InstanceTransfer& transfer, DcmDataset& keys,
                   const std::string& destinationAet);

} // namespace lw::pacs::detail
