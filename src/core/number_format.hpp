#pragma once
// Numbers in messages (errors, warnings, progress lines): one formatter, so that a value reads
// as a user would write it wherever it is printed.
#include <string>

namespace shpb {

// The shortest text that reads back as the same double when that has at most 9 significant
// digits ("1e-05", "0.05", "2.5e+11", "1e+300"); a computed value with more digits is rounded to
// 6 ("0.3", not "0.30000000000000004"). Never "-0" (a zero is "0") and never the hundreds of
// digits of printf's %f for 1e300; "nan", "inf" and "-inf" for the non-finite.
std::string format_number(double value);

// `value` to `digits` significant digits ("%.*g"), or to as many more as make its last digit no
// coarser than `resolution`: a time on a record's clock to its sample interval. A DAQ's clock that
// counts from when it was armed puts a 1 MS/s record at 58.3 s, where 6 digits ("5.83131e+07 us")
// name no sample; this prints "58313055 us". Values that already resolve it print as "%.*g" does.
std::string format_resolved(double value, double resolution, int digits);

// "[lo, hi]" with the numbers of format_number, "(" or ")" at an open end: "[1e-05, 0.05]".
std::string format_range(double lo, double hi, bool lo_open = false, bool hi_open = false);

}  // namespace shpb
