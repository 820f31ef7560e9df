// Writes a file so that readers only ever see the old or the complete new content: the data goes
// to a temporary file in the same directory, which is renamed over the target once complete.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string_view>

namespace toonwater {

class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Replaces `path` with `contents` atomically. Throws OutputError naming the file on failure, in
// which case `path` is untouched and no temporary file is left behind.
void write_file_atomically(const std::filesystem::path& path, std::string_view contents);

}  // namespace toonwater
