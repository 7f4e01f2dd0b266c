#pragma once

// C-FIND on an open association, shared by the queries and the retrieve (which asks for the
// instances first on the association it then retrieves on).
#include "association.h"

#include <dcmtk/dcmdata/dcdatset.h>
#include <vector>

namespace lw::pacs::detail {

// The identifiers of every pending response, in order. Checks `cancel` at each response and
// sends C-CANCEL once it is set, then throws core::Cancelled after the PACS's final answer.
// Throws PacsError when the PACS answers with a failure status or the exchange breaks.
std::vector<DcmDataset> findOnAssociation(Association& association, DcmDataset& keys,
                                          const core::CancelToken* cancel);

// The Study Root C-FIND context, for an Association that only queries.
PresentationContext studyRootFindContext();

DcmDataset instanceKeys(const std::string& studyUid, const std::string& seriesUid);
InstanceRecord instanceRecord(DcmDataset& identifier);

} // namespace lw::pacs::detail
