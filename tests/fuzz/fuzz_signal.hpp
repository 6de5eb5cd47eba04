#pragma once
// Shared body of the signal importer fuzzers: the input becomes a file in `format`, and the first
// byte (removed) picks which columns are asked for. Contract: read_signal_columns returns
// columns of equal length on an increasing, finite time base with finite samples, or throws
// InputError.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/error.hpp"
#include "core/signal_reader.hpp"
#include "fuzz_file.hpp"

namespace shpb_fuzz {

// A broken contract names itself before aborting (the fuzzer keeps the input).
#define SHPB_FUZZ_REQUIRE(ok)                                                      \
  do {                                                                             \
    if (!(ok)) {                                                                   \
      std::fprintf(stderr, "fuzz contract broken: %s (line %d)\n", #ok, __LINE__); \
      std::abort();                                                                \
    }                                                                              \
  } while (0)

inline int fuzz_signal(const std::uint8_t* data, std::size_t size, shpb::SignalFormat format,
                       const std::string& file_name) {
  if (size == 0) return 0;
  const std::uint8_t pick = data[0];
  const auto file = write_input(data + 1, size - 1, file_name);
  shpb::SignalRequest request;
  request.file = file;
  request.format = format;
  // Columns: by index (low bits), by a name the seeds use (bit 4), the time column named (bit 5),
  // a time unit of microseconds (bit 6), the workbook's sheet "signals" (bit 7; else the first).
  request.columns.push_back(shpb::ColumnRef{"", pick & 7});
  if (pick & 16) request.columns.push_back(shpb::ColumnRef{"ch2", std::nullopt});
  if (pick & 32) request.time_column = shpb::ColumnRef{"time_s", std::nullopt};
  if (pick & 64) request.time_unit_s = 1e-6;
  if (pick & 128) request.sheet = "signals";
  try {
    const shpb::SignalColumns s = shpb::read_signal_columns(request);
    SHPB_FUZZ_REQUIRE(s.time_s.size() >= 2);
    SHPB_FUZZ_REQUIRE(std::isfinite(s.dt_s) && s.dt_s > 0);
    for (std::size_t i = 0; i < s.time_s.size(); ++i) {
      SHPB_FUZZ_REQUIRE(std::isfinite(s.time_s[i]));
      if (i > 0) SHPB_FUZZ_REQUIRE(s.time_s[i] > s.time_s[i - 1]);
    }
    SHPB_FUZZ_REQUIRE(s.values.size() == request.columns.size());
    for (const auto& column : s.values) {
      SHPB_FUZZ_REQUIRE(column.size() == s.time_s.size());
      for (double v : column) SHPB_FUZZ_REQUIRE(std::isfinite(v));
    }
  } catch (const shpb::InputError&) {
  }
  return 0;
}

}  // namespace shpb_fuzz
