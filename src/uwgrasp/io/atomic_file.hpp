#pragma once
// Output files appear whole or not at all: write to a temporary sibling, then rename.
#include <functional>
#include <string>

namespace uwgrasp::io {

// Calls write(tmp_path) and renames tmp_path to path; on any failure removes tmp_path and
// throws Error naming `path`.
void write_atomically(const std::string& path, const std::function<void(const std::string&)>& write);

// Writes text to path atomically.
void write_text(const std::string& path, const std::string& text);

}  // namespace uwgrasp::io
