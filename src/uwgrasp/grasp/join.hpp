#pragma once
// Lists built in parallel, one per task, joined in task order: the same elements in the same
// order as one serial pass, whatever the thread count. Internal to grasp/.
#include <cstddef>
#include <vector>

namespace uwgrasp::grasp {

// Appends every part to out, in order, with one reservation for the whole.
template <class T>
void join_in_order(const std::vector<std::vector<T>>& parts, std::vector<T>& out) {
  std::size_t total = out.size();
  for (const auto& part : parts) total += part.size();
  out.reserve(total);
  for (const auto& part : parts) out.insert(out.end(), part.begin(), part.end());
}

}  // namespace uwgrasp::grasp
