#include "uwgrasp/io/atomic_file.hpp"

#include <unistd.h>

#include <array>
#include <cerrno>
#include <atomic>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp::io {

namespace {
// The temporary files being written, for the signal handler to remove: fixed slots of plain
// char arrays, because a handler may only call async-signal-safe functions (unlink, raise).
constexpr std::size_t kSlots = 64, kPathMax = 4096;
struct Slot {
  std::atomic<int> state{0};  // 0 free, 1 being filled or emptied, 2 holds a path
  char path[kPathMax];
};
std::array<Slot, kSlots> g_slots;

// Claims a slot for `tmp`; -1 when all are taken or the path is too long (the file is then
// only left behind on a signal, never a partial output).
int remember(const std::string& tmp) {
  if (tmp.size() >= kPathMax) return -1;
  for (std::size_t i = 0; i < kSlots; ++i) {
    int expected = 0;
    if (!g_slots[i].state.compare_exchange_strong(expected, 1)) continue;
    std::memcpy(g_slots[i].path, tmp.c_str(), tmp.size() + 1);
    g_slots[i].state.store(2);
    return int(i);
  }
  return -1;
}

void forget(int slot) {
  if (slot >= 0) g_slots[std::size_t(slot)].state.store(0);
}

extern "C" void remove_temporaries_and_reraise(int sig) {
  for (auto& s : g_slots) {
    int expected = 2;
    if (s.state.compare_exchange_strong(expected, 1)) ::unlink(s.path);
  }
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}
}  // namespace

std::string reason() { return errno ? std::string(" (") + std::strerror(errno) + ")" : std::string(); }

void remove_partial_outputs_on_signal() {
  for (const int sig : {SIGINT, SIGTERM, SIGHUP}) std::signal(sig, remove_temporaries_and_reraise);
  // A file size limit (ulimit -f) then fails the write with EFBIG, which is reported as an Error
  // naming the file, instead of killing the process.
  std::signal(SIGXFSZ, SIG_IGN);
}

void write_atomically(const std::string& path,
                      const std::function<void(const std::string&)>& write) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  std::string tmp_name = ".";
  tmp_name += target.filename().string();
  tmp_name += ".tmp-";
  tmp_name += std::to_string(::getpid());
  const fs::path tmp = target.parent_path() / tmp_name;
  // Say why up front when the folder is the problem: the writers below only report failure.
  const fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  std::error_code folder_ec;
  if (!fs::is_directory(folder, folder_ec)) throw Error(path + ": cannot write (no folder " + folder.string() + ")");
  if (::access(folder.c_str(), W_OK) != 0)
    throw Error(path + ": cannot write (" + std::strerror(errno) + ": " + folder.string() + ")");
  const int slot = remember(tmp.string());
  try {
    write(tmp.string());
    std::error_code ec;
    fs::rename(tmp, target, ec);
    if (ec) throw Error(path + ": cannot write (" + ec.message() + ")");
  } catch (...) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    forget(slot);
    throw;
  }
  forget(slot);
}

void write_text(const std::string& path, const std::string& text) {
  write_atomically(path, [&](const std::string& tmp) {
    std::ofstream f(tmp, std::ios::binary);
    errno = 0;
    f << text;
    f.close();
    if (!f) throw Error(path + ": cannot write" + reason());
  });
}

}  // namespace uwgrasp::io
