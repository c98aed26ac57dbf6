#pragma once
// Validation of JSON job spec files, field by field, before protobuf's JSON parser sees them
// (its messages do not say which field is wrong). Walks the JSON against the JobSpec message
// descriptor, so every field of idl/job.proto is covered: unknown fields, wrong types, two
// members of one oneof, and the ranges of numbers (positive periods and gains, probabilities
// in [0, 1], non-negative durations).

#include <string>

#include "idl/job.pb.h"

namespace netmc::cli {

// Throws std::invalid_argument("<origin>: <field.path>: expected ..., got ...").
void validate_job_spec_json(const std::string& json, const std::string& origin);
// Validates, then parses.
netmc::v1::JobSpec parse_job_spec_file_text(const std::string& json, const std::string& origin);

}  // namespace netmc::cli
