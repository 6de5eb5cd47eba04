// One record as instruments and spreadsheets export it (docs/validation.md, "Lab records without
// traps"): the classic experiment's simulated gauges written as a LabVIEW .lvm whose time column
// has LabVIEW's 6 decimals, a Rigol CSV (sample numbers under a Start/Increment header), a file
// with a column of NaN and a footer line, an .xlsx whose chart sheet comes first; each read by
// `process` and judged against the same record read from a plain CSV with its time column.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "classic_record.hpp"
#include "lab_record.hpp"
#include "run_shpb.hpp"
#include "write_xlsx.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_app_test_instrument_exports {

namespace fs = std::filesystem;
using nlohmann::json;
using shpb_test::has_warning;
using shpb_test::read_columns;
using shpb_test::read_text;
using shpb_test::run_shpb;
using shpb_test::RunResult;
using shpb_test::scratch_dir;
using shpb_test::summary;
using shpb_test::classic::check_refused;
using shpb_test::classic::check_same_curve;
using shpb_test::classic::classic_reading;
using shpb_test::classic::process;
using shpb_test::classic::processed;
using shpb_test::classic::record_rows;
using shpb_test::classic::simulated;

namespace {

// Stamps rounded to 1 µs at 10 MS/s: the rebuilt clock's start is their least-squares line's,
// which the ties (every tenth stamp, rounded one way) move by less than half a sample.
constexpr double kRebuiltStart_s = 0.5e-7;
// The scope's pre-trigger: its time 0 is 100 µs into the simulated record.
constexpr double kTrigger_s = 100e-6;

// The classic record simulated into dir/sim, and processed from its gauges.csv into dir/timed.
std::vector<std::vector<double>> simulated_and_timed(const fs::path& dir) {
  const auto rec = simulated(dir);
  processed(classic_reading(dir, "timed.json", dir / "sim/gauges.csv", nullptr), dir / "timed");
  return rec;
}

// "%.6f" as LabVIEW writes its values.
std::string six_decimals(double v) {
  char s[40];
  std::snprintf(s, sizeof s, "%.6f", v);
  return s;
}

}  // namespace

TEST_CASE("Stamps rounded to the µs at 10 MS/s are read: a plain column and LabVIEW's X_Value",
          "[app][process][timebase]") {
  // LabVIEW writes 6 decimals: at 10 MS/s ten rows share each µs stamp, and every tenth lies
  // exactly between two µs, rounded one way (which moved the stamps' least-squares line by a
  // third of a sample, and a clock judged from it refused them as a gap).
  const fs::path d = scratch_dir("exports_rounded_stamps");
  const auto rec = simulated_and_timed(d);
  std::ostringstream rows;
  rows.precision(17);
  for (std::size_t i = 0; i < rec[0].size(); ++i)
    rows << six_decimals(rec[0][i] - kTrigger_s) << "\t" << rec[1][i] << "\t" << rec[2][i]
         << "\r\n";
  SECTION("a plain column") {
    std::ofstream(d / "us.txt") << "t_s\tincident\ttransmitted\r\n" << rows.str();
    const auto scene = classic_reading(d, "plain.json", d / "us.txt", nullptr);
    processed(scene, d / "plain");
    CHECK(has_warning(summary(d / "plain"), "the column was rounded"));
    check_same_curve(d / "timed", d / "plain", -kTrigger_s, kRebuiltStart_s);
  }
  SECTION("LabVIEW's X_Value under its Delta_X") {
    std::ofstream(d / "record.lvm")
        << "LabVIEW Measurement\t\r\nWriter_Version\t2\r\nReader_Version\t2\r\nSeparator\tTab\r\n"
           "Decimal_Separator\t.\r\nMulti_Headings\tNo\r\nX_Columns\tOne\r\n"
           "Time_Pref\tRelative\r\n***End_of_Header***\t\r\n\t\r\nChannels\t2\t\t\r\n"
           "Samples\t8001\t8001\t\r\nX_Dimension\tTime\tTime\t\r\n"
           "X0\t-1.0000000000000000E-4\t-1.0000000000000000E-4\t\r\n"
           "Delta_X\t1.000000E-7\t1.000000E-7\t\r\n***End_of_Header***\t\t\t\r\n"
           "X_Value\tincident\ttransmitted\tComment\r\n"
        << rows.str();
    const auto scene = classic_reading(d, "lvm.json", d / "record.lvm", nullptr);
    processed(scene, d / "lvm");
    check_same_curve(d / "timed", d / "lvm", -kTrigger_s, kRebuiltStart_s);
  }
}

TEST_CASE("A Rigol CSV is read on its Start and Increment header, channels by name",
          "[app][process][timebase]") {
  // Rigol's DS1000Z CSV: names, then units with the time base beside them; the first column
  // numbers the samples, and every data row ends with a comma.
  const fs::path d = scratch_dir("exports_rigol");
  const auto rec = simulated_and_timed(d);
  auto numbered = rec;  // the first column numbers the samples
  for (std::size_t i = 0; i < rec[0].size(); ++i) numbered[0][i] = static_cast<double>(i);
  std::ofstream(d / "rigol.csv") << "X,CH1,CH2,Start,Increment,\n"
                                    "Sequence,Volt,Volt,-1.000000e-04,1.000000e-07\n"
                                 << record_rows(numbered, {",", ","}, ",\n");
  SECTION("the header's time base, said in a warning") {
    const auto scene = classic_reading(d, "s.json", d / "rigol.csv", nullptr, "CH1", "CH2", "V");
    processed(scene, d / "out");
    CHECK(has_warning(summary(d / "out"), "line 2 (Increment)"));
    CHECK(has_warning(summary(d / "out"), "line 2 (Start)"));
    check_same_curve(d / "timed", d / "out", -kTrigger_s);
  }
  SECTION("the scene's interval, which the header's must match") {
    const auto scene =
        classic_reading(d, "s.json", d / "rigol.csv",
                        {{"interval", "0.1 us"}, {"start", "-100 us"}}, "CH1", "CH2", "V");
    processed(scene, d / "out");
    check_same_curve(d / "timed", d / "out", -kTrigger_s);
    const auto wrong =
        classic_reading(d, "w.json", d / "rigol.csv", {{"interval", "0.2 us"}}, "CH1", "CH2", "V");
    check_refused(process(wrong, d / "wrong"), {"rigol.csv", "line 2 (Increment)"});
  }
}

TEST_CASE("A column of NaN beside the samples and a footer line leave the record readable",
          "[app][process][csv]") {
  // A channel not recorded exported as NaN in every row, and "End of data" after the last row:
  // every row held a text, and the file was refused as one without numbers; the footer was read
  // as a sample.
  const fs::path d = scratch_dir("exports_nan_footer");
  const auto rec = simulated_and_timed(d);
  const std::string text =
      "time_s,incident,temperature,transmitted\n" + record_rows(rec, {",", ",NaN,"});
  const std::string footer_line = std::to_string(rec[0].size() + 2);
  SECTION("read, the footer said by its line") {
    std::ofstream(d / "nan.csv") << text << "End of data\n";
    const auto scene = classic_reading(d, "s.json", d / "nan.csv", nullptr);
    processed(scene, d / "out");
    CHECK(
        has_warning(summary(d / "out"), "line " + footer_line + " after the data holds no number"));
    check_same_curve(d / "timed", d / "out", 0);
  }
  SECTION("the column of NaN read is refused by line and column") {
    std::ofstream(d / "nan.csv") << text;
    const auto scene = classic_reading(d, "s.json", d / "nan.csv", nullptr, "temperature");
    check_refused(process(scene, d / "out"), {"nan.csv: line 2, column 3", "NaN"});
  }
  SECTION("a last line cut to a sign is no footer") {
    std::ofstream(d / "nan.csv") << text << "-";
    const auto scene = classic_reading(d, "s.json", d / "nan.csv", nullptr);
    check_refused(process(scene, d / "out"), {"nan.csv: line " + footer_line + ", column 1"});
  }
}

TEST_CASE("Fortran's D exponents are read and a channel header's rows of numbers refused",
          "[app][process][csv]") {
  // A Fortran program's DOUBLE PRECISION columns ("0.1000000000000000D-06") were refused by value
  // and line; a catman-style export's sample rates and channel numbers under the names were
  // refused as a time going backwards (line 3: 0 s after 1e+07 s).
  const fs::path d = scratch_dir("exports_fortran_catman");
  const auto rec = simulated_and_timed(d);
  SECTION("D exponents give the plain CSV's curve") {
    std::ofstream out(d / "fortran.txt");
    out << " time_s incident transmitted\n";
    char field[40];
    for (std::size_t i = 0; i < rec[0].size(); ++i) {
      for (const auto& column : rec) {
        std::snprintf(field, sizeof field, " %.16E", column[i]);
        std::string f = field;
        std::replace(f.begin(), f.end(), 'E', 'D');
        out << f;
      }
      out << "\n";
    }
    out.close();
    const auto scene = classic_reading(d, "s.json", d / "fortran.txt", nullptr);
    processed(scene, d / "out");
    check_same_curve(d / "timed", d / "out", 0);
  }
  SECTION("a channel header's rows of numbers are refused by line with their cause") {
    std::ofstream(d / "catman.txt") << "time_s\tincident\ttransmitted\n"
                                       "10000000\t10000000\t10000000\n0\t1\t2\n"
                                    << record_rows(rec, {"\t", "\t"});
    const auto scene = classic_reading(d, "s.json", d / "catman.txt", nullptr);
    check_refused(process(scene, d / "out"),
                  {"catman.txt: line 2, column 1 (\"time_s\"): \"10000000\"",
                   "not on the clock of the samples below", "lines 2–3 under the header (line 1)",
                   "export without the channel header"});
  }
}

TEST_CASE("A sample count on the first line is read and a channel number over untimed rows refused",
          "[app][process][csv]") {
  // Scope exports that write the number of points first: refused as a header row of numbers
  // ("no number in this row, above the samples"). A file without a time column
  // (measurement.time.interval) read a channel-number row under its names as the first samples:
  // a strain of 1 and 2, then refused as a pulse at the record's start.
  const fs::path d = scratch_dir("exports_count_channels");
  const auto rec = simulated_and_timed(d);
  SECTION("the count of the samples below, then the names") {
    std::ofstream(d / "count.csv") << rec[0].size() << "\ntime_s,incident,transmitted\n"
                                   << record_rows(rec);
    const auto scene = classic_reading(d, "s.json", d / "count.csv", nullptr);
    processed(scene, d / "out");
    CHECK(has_warning(summary(d / "out"), "line 1 holds " + std::to_string(rec[0].size()) +
                                              " alone, the number of samples below it"));
    check_same_curve(d / "timed", d / "out", 0);
    std::ofstream(d / "short.csv") << rec[0].size() + 1 << "\ntime_s,incident,transmitted\n"
                                   << record_rows(rec);
    const auto wrong = classic_reading(d, "w.json", d / "short.csv", nullptr);
    check_refused(process(wrong, d / "wrong"),
                  {"short.csv: line 1: \"" + std::to_string(rec[0].size() + 1) + "\"",
                   "a header's sample count, but lines 3–" + std::to_string(rec[0].size() + 2) +
                       " hold " + std::to_string(rec[0].size()) + " samples"});
  }
  SECTION("a channel-number row under the names of untimed samples") {
    const std::vector<std::vector<double>> untimed(rec.begin() + 1, rec.end());
    std::ofstream(d / "untimed.csv") << "incident,transmitted\n1,2\n"
                                     << record_rows(untimed, {","});
    const auto scene = classic_reading(d, "u.json", d / "untimed.csv", {{"interval", "0.1 us"}});
    check_refused(process(scene, d / "out"),
                  {"untimed.csv: line 2, column 1 (\"incident\"): \"1\"",
                   "off the level of the samples below", "export without the channel header"});
  }
}

TEST_CASE("A TranAX export's channels are read by the names above its quantities and units",
          "[app][process][csv]") {
  // Elsys TranAX, as a rock-testing lab's Carrara marble record is written: each line quoted
  // whole, semicolons, decimal commas, metadata, then the channel names ("Kanal"), a row of
  // quantities ("Zeit;Signal;Signal;") and the units. A name holding a comma was refused by the
  // scene ("must not contain a comma"), and the names two rows above the units were not searched:
  // "no such column; the header has "Zeit", "Signal", "Signal"".
  const fs::path d = scratch_dir("exports_tranax");
  const auto rec = simulated_and_timed(d);
  const std::string incident = "DMS1 A (Eingangsstab 1,0m) (0.A1)";
  const std::string transmitted = "DMS2 A (Ausgangsstab 1m) (0.A3)";
  std::ofstream out(d / "tranax.csv", std::ios::binary);
  out << "\"Starttime;22.03.2016 12:02:33\"\r\n\"TriggerSample;-21762\"\r\n"
         "\"Samplerate;10000000 Hz\"\r\n\"Blocklength;"
      << rec[0].size() << "\"\r\n\"Kanal;" << incident << ";" << transmitted
      << ";\"\r\n\"Zeit;Signal;Signal;\"\r\n\"s;V;V;\"\r\n";
  char field[40];
  for (std::size_t i = 0; i < rec[0].size(); ++i) {
    out << "\"";
    for (std::size_t k = 0; k < rec.size(); ++k) {
      std::snprintf(field, sizeof field, "%.16e", rec[k][i]);
      std::string f = field;
      std::replace(f.begin(), f.end(), '.', ',');
      out << (k ? ";" : "") << f;
    }
    out << "\"\r\n";
  }
  out.close();
  const auto scene =
      classic_reading(d, "s.json", d / "tranax.csv", nullptr, incident, transmitted, "V");
  processed(scene, d / "out");
  check_same_curve(d / "timed", d / "out", 0);
  const auto quantity =
      classic_reading(d, "q.json", d / "tranax.csv", nullptr, "Signal", transmitted, "V");
  check_refused(process(quantity, d / "quantity"),
                {"tranax.csv: line 6", "column \"Signal\"", "several header columns match"});
}

TEST_CASE("A workbook's chart sheet in front of its data is passed over by default",
          "[app][process][excel]") {
  // A plot saved as a chart sheet before the signals' sheet: "the first sheet" was the chart,
  // refused as an empty sheet.
  const fs::path d = scratch_dir("exports_chart_sheet");
  const auto rec = simulated_and_timed(d);
  std::vector<std::string> shared;
  auto parts = shpb_test::xlsx_parts(
      shpb_test::xlsx_rows("time_s,incident,transmitted\n" + record_rows(rec), shared), shared);
  const std::string rels = "http://schemas.openxmlformats.org/officeDocument/2006/relationships";
  for (auto& [name, text] : parts) {
    if (name == "xl/workbook.xml")
      text =
          "<?xml version=\"1.0\" encoding=\"UTF-8\"?><workbook "
          "xmlns=\"http://schemas.openxmlformats.org/spreadsheetml/2006/main\" xmlns:r=\"" +
          rels +
          "\"><sheets><sheet name=\"plot\" sheetId=\"3\" r:id=\"rId3\"/>"
          "<sheet name=\"signals\" sheetId=\"2\" r:id=\"rId2\"/></sheets></workbook>";
    if (name == "xl/_rels/workbook.xml.rels")
      text =
          "<?xml version=\"1.0\" encoding=\"UTF-8\"?><Relationships "
          "xmlns=\"http://schemas.openxmlformats.org/package/2006/relationships\">"
          "<Relationship Id=\"rId2\" Type=\"" +
          rels +
          "/worksheet\" Target=\"worksheets/sheet2.xml\"/><Relationship Id=\"rId3\" Type=\"" +
          rels + "/chartsheet\" Target=\"chartsheets/sheet1.xml\"/></Relationships>";
  }
  parts.emplace_back("xl/chartsheets/sheet1.xml",
                     "<?xml version=\"1.0\" encoding=\"UTF-8\"?><chartsheet "
                     "xmlns=\"http://schemas.openxmlformats.org/spreadsheetml/2006/main\">"
                     "<sheetViews><sheetView workbookViewId=\"0\"/></sheetViews></chartsheet>");
  shpb_test::write_zip(d / "signals.xlsx", parts);
  const auto scene = classic_reading(d, "s.json", d / "signals.xlsx", nullptr);
  processed(scene, d / "out");
  check_same_curve(d / "timed", d / "out", 0);
  const auto chart = classic_reading(d, "c.json", d / "signals.xlsx", nullptr, "incident",
                                     "transmitted", "strain", {{"sheet", "plot"}});
  check_refused(process(chart, d / "chart"),
                {"signals.xlsx", "\"plot\"", "a chart sheet", "worksheets are \"signals\""});
}

}  // namespace tests_app_test_instrument_exports
