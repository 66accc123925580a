#pragma once
// Output files appear whole or not at all: write to a temporary sibling, then rename.
#include <functional>
#include <string>

namespace uwgrasp::io {

// Calls write(tmp_path) and renames tmp_path to path; on any failure removes tmp_path and
// throws Error naming `path`.
void write_atomically(const std::string& path, const std::function<void(const std::string&)>& write);

// Installs handlers for SIGINT, SIGTERM and SIGHUP that remove the temporary files of writes in
// progress before the signal ends the process as it would have; and ignores SIGXFSZ, so that a
// file size limit fails the write (an Error) rather than killing the process. For programs.
void remove_partial_outputs_on_signal();

// " (the C library's reason)" for the last failed system call, or "" when errno is 0: set
// errno = 0 before a write whose failure is only a return value.
std::string reason();

// Writes text to path atomically.
void write_text(const std::string& path, const std::string& text);

}  // namespace uwgrasp::io
