// libFuzzer target: the csv signal importer (core/signal_*.cpp) through read_signal_columns.
#include "fuzz_signal.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return shpb_fuzz::fuzz_signal(data, size, shpb::SignalFormat::kCsv, "signals.csv");
}
