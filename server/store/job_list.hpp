#pragma once
// The job history as the management protocol lists it (netmc.v1.JobList), from the job store's
// rows: one conversion for netmc-server (`netmc jobs`) and for `netmc jobs --state-dir`, which
// reads a store without a server, so both print the same list.

#include <vector>

#include "idl/management.pb.h"
#include "server/store/job_store.hpp"

namespace netmc::store {

// The request's filter, checked: throws std::invalid_argument naming the field.
JobFilter job_filter(const netmc::v1::ListJobs& request);

// One JobStatus per stored job, in the order given; `persistent`: they come from a job store.
netmc::v1::JobList job_list(const std::vector<StoredJob>& jobs, bool persistent);

}  // namespace netmc::store
