#pragma once
// Temporary files left by a process that died before it could remove them (SIGKILL, a power
// cut): PendingFile's NAME.tmpPID_N. The next process that writes into the same folder removes
// them (docs/reliability.md, "Nothing half-written").

#include <sys/types.h>

#include <filesystem>
#include <optional>
#include <string_view>

namespace stochnav {

/// The process id in a PendingFile temporary file's name, "NAME.tmpPID_N" (PID and N decimal),
/// or nothing when `file_name` does not have that form.
std::optional<pid_t> temporary_file_owner(std::string_view file_name);

/// Takes a shared lock (flock) on the temporary file `path` for as long as the returned
/// descriptor is open (-1 if the file cannot be opened): the mark that its writer is alive,
/// which remove_stale_temporaries respects even where process ids mean nothing (a folder
/// shared over NFS by several machines).
int lock_temporary_file(const std::filesystem::path& path);

/// Removes the regular files of `folder` (not of its subfolders) named NAME.tmpPID_N whose
/// process PID is not alive on this machine (kill(PID, 0) fails with ESRCH) and that no process
/// holds locked; anything else is left alone, and errors are ignored (this is housekeeping).
/// Does the work once per folder and process; thread-safe.
void remove_stale_temporaries(const std::filesystem::path& folder);

}  // namespace stochnav
