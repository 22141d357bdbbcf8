// libFuzzer's entry for one target (LZB_FUZZ_TARGET, e.g. fuzzToml), built by scripts/fuzz.sh
// with clang and -fsanitize=fuzzer,address,undefined. An exception other than InputError is a
// finding: abort, so libFuzzer keeps the input.
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "tests/fuzz/fuzz_targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    return lzb::fuzz::LZB_FUZZ_TARGET(data, size);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lzb fuzz: bad input was not refused with an InputError: %s\n", e.what());
    std::abort();
  }
}
