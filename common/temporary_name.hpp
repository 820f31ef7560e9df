// Names of the temporary files and directories toonwater makes beside its outputs, and the
// proof that an entry so named is toonwater's own.
//
// A temporary of NAME is ".NAME.tmp-H-P-R-C": H identifies this machine (8 hex digits of a hash
// of its host name), P is the process id, R 16 random hex digits and C a check of all the rest
// (8 hex digits of a 64-bit FNV-1a hash). A user's file that merely looks like one
// (".notes.tmp-123") has no valid check, so it is never taken for a temporary; R makes two
// processes' names differ even on a shared directory where their ids collide.
//
// A temporary is stale, and may be removed by a later run, only when it is toonwater's (valid
// check), was made on this machine (a farm's shared directory holds other hosts' temporaries,
// whose processes cannot be seen from here) and its process is gone.
#pragma once

#include <string>
#include <string_view>

namespace toonwater {

// ".NAME.tmp-H-P-R-C" for this process: at most 100 bytes of `name` are kept, so that the
// result stays within a file system's 255-byte limit whatever the name.
std::string temporary_name(std::string_view name);

// Whether `filename` (no directory) is a temporary name toonwater made (its check holds), and,
// when it is, the NAME it was made for.
bool is_own_temporary(std::string_view filename, std::string* name = nullptr);

// Whether `filename` is toonwater's temporary, made on this machine by a process that is gone.
bool is_stale_temporary(std::string_view filename);

}  // namespace toonwater
