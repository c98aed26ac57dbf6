#pragma once
// The cancel tokens of the jobs this user submitted: `netmc submit` saves each job's token,
// `netmc cancel` reads it, so the submitter can cancel the job from any terminal. One file a
// job, named by the server address and the job id, readable by the user only (0600) in a
// directory of the user's only (0700): $XDG_STATE_HOME/netmc/jobs, else ~/.local/state/netmc/jobs.
// The path never comes from the server. See docs/operations/hostile-networks-and-clients.md, Jobs.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

namespace netmc::cli {

// Where the token of `job_id` on `server` (as --server names it) is kept, or nullopt when
// neither $XDG_STATE_HOME (absolute) nor $HOME is set.
std::optional<std::filesystem::path> job_token_path(const std::string& server, std::uint64_t job_id);

// Saves the token (creating the directory 0700 if need be) and returns the file's path. Throws
// std::runtime_error naming the path when it cannot.
std::filesystem::path save_job_token(const std::string& server, std::uint64_t job_id, const std::string& token);

// The saved token of `job_id` on `server`, or nullopt if none was saved.
std::optional<std::string> saved_job_token(const std::string& server, std::uint64_t job_id);

// Deletes the saved token of `job_id` on `server` (a job that is cancelled needs it no more);
// true if there was one.
bool forget_job_token(const std::string& server, std::uint64_t job_id);

}  // namespace netmc::cli
