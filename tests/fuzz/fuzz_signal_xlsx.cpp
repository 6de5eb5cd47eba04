// libFuzzer target: the .xlsx signal importer (core/signal_xlsx.cpp: libzip and expat) through
// read_signal_columns.
#include "fuzz_signal.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return shpb_fuzz::fuzz_signal(data, size, shpb::SignalFormat::kCsv, "signals.xlsx");
}
