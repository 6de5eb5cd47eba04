#pragma once
// The time base a signal file's header states (Yokogawa's HResolution/HOffset/HUnit rows, Rigol's
// Start/Increment, LabVIEW's Delta_X/X0) for a file without a time column, and the scene's checked
// against it.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/signal_reader.hpp"
#include "core/signal_spec.hpp"
#include "core/signal_text.hpp"

namespace shpb {

// The time base of a file without a time column: the scene's (measurement.time.interval), checked
// against a header that states one, or the header's (Yokogawa, Rigol), with a warning naming its
// rows.
// LabVIEW's X0 may be an absolute time (seconds since 1904) and its Delta_X one segment's of
// several: refused, naming the row, for the scene to state the interval.
// Its TraceName row (Rigol: the names left of Start) names the channels.
struct FileClock {
  std::optional<SampleClock> clock;
  std::optional<TextRow> trace_names;
};
FileClock file_clock(const DelimitedText& text, std::size_t first_data,
                     const SignalRequest& request, std::vector<std::string>& warnings);

}  // namespace shpb
