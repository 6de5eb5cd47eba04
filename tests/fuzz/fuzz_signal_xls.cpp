// libFuzzer target: the .xls signal importer (core/signal_spreadsheet.cpp) through
// read_signal_columns. FreeXL runs in a child process there (a crash in it is an InputError
// here), so what this target checks is the rest: the OLE2 check, the child's answer decoded and
// the sheet's limits, and that no input reaches a crash or hang of this process.
#include "fuzz_signal.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return shpb_fuzz::fuzz_signal(data, size, shpb::SignalFormat::kCsv, "signals.xls");
}
