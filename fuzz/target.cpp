// One libFuzzer target: UWGRASP_FUZZ_TARGET names the function of fuzz/inputs.hpp it feeds.
#include <cstddef>
#include <cstdint>

#include "fuzz/inputs.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  uwgrasp::fuzz::UWGRASP_FUZZ_TARGET(uwgrasp::fuzz::Bytes(data, size));
  return 0;
}
