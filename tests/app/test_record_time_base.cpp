// Records without a time column (docs/scene-format.md, measurement.time.interval): the classic
// experiment's simulated gauges written with their channels only, as LabVIEW and DAQ exports and
// workbooks of channels hold them, or under Yokogawa's ASCII header, run through the executable
// and judged against the same record read with its time column; and every refusal of a time base
// given twice or out of range, one line and exit 2.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
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
namespace tests_app_test_record_time_base {

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
using shpb_test::classic::kSameRecord;
using shpb_test::classic::kSource;
using shpb_test::classic::process;
using shpb_test::classic::processed;
using shpb_test::classic::simulated;

namespace {

// The record's channels only, `prefix` before each row (Yokogawa's empty key column: ","),
// written with 17 digits under `header`.
std::string channels_only(const std::vector<std::vector<double>>& rec, const std::string& header,
                          const std::string& prefix = "") {
  std::ostringstream s;
  s.precision(17);
  s << header;
  for (std::size_t i = 0; i < rec[0].size(); ++i)
    s << prefix << rec[1][i] << "," << rec[2][i] << "\n";
  return s.str();
}

}  // namespace

TEST_CASE("A record without a time column gives the timed record's curve on its interval",
          "[app][process][timebase]") {
  const fs::path d = scratch_dir("timebase_channels");
  const auto rec = simulated(d);
  const fs::path timed =
      classic_reading(d, "timed.json", d / "sim/gauges.csv", {{"column", "time_s"}, {"unit", "s"}});
  processed(timed, d / "timed");
  const std::string text = channels_only(rec, "incident,transmitted\n");
  std::ofstream(d / "channels.csv") << text;
  shpb_test::write_xlsx(d / "channels.xlsx", text);
  SECTION("CSV, the interval given") {
    const auto scene = classic_reading(d, "s.json", d / "channels.csv", {{"interval", "0.1 us"}});
    processed(scene, d / "out");
    check_same_curve(d / "timed", d / "out", 0);
  }
  SECTION("CSV, the sample rate given") {
    const auto scene = classic_reading(d, "s.json", d / "channels.csv", {{"rate", "10 MHz"}});
    processed(scene, d / "out");
    check_same_curve(d / "timed", d / "out", 0);
  }
  SECTION("CSV, a pre-trigger start: every time 20 us earlier, the same curve") {
    const auto scene = classic_reading(d, "s.json", d / "channels.csv",
                                       {{"interval", "0.1 us"}, {"start", "-20 us"}});
    processed(scene, d / "out");
    check_same_curve(d / "timed", d / "out", -20e-6);
  }
  SECTION("an .xlsx workbook of channels, by index") {
    const auto scene =
        classic_reading(d, "s.json", d / "channels.xlsx", {{"interval", "0.1 us"}}, 0, 1);
    json s = json::parse(read_text(scene));
    s["measurement"]["sheet"] = "signals";  // the workbook's second sheet (write_xlsx.hpp)
    std::ofstream(scene) << s.dump(2);
    processed(scene, d / "out");
    check_same_curve(d / "timed", d / "out", 0);
  }
  SECTION("each channel in its own file") {
    std::ofstream(d / "incident.csv") << channels_only(rec, "incident,unused\n");
    json s = json::parse(
        read_text(classic_reading(d, "s.json", d / "channels.csv", {{"interval", "0.1 us"}})));
    s["measurement"]["channels"][0]["file"] = (d / "incident.csv").string();
    std::ofstream(d / "s.json") << s.dump(2);
    processed(d / "s.json", d / "out");
    check_same_curve(d / "timed", d / "out", 0);
  }
  SECTION("a campaign of that test") {
    classic_reading(d, "s.json", d / "channels.csv", {{"interval", "0.1 us"}});
    std::ofstream(d / "campaign.json")
        << json{{"name", "untimed"}, {"tests", {{{"scene", "s.json"}, {"name", "t1"}}}}}.dump();
    const RunResult r = run_shpb({"process", "--campaign", (d / "campaign.json").string(), "-o",
                                  (d / "out").string(), "-q"});
    INFO(r.err);
    REQUIRE(r.code == 0);
    check_same_curve(d / "timed", d / "out/t1", 0);
  }
  SECTION("compare: the same comparison") {
    const auto scene = classic_reading(d, "s.json", d / "channels.csv", {{"interval", "0.1 us"}});
    const auto compare = [](const fs::path& s, const fs::path& out) {
      return run_shpb({"compare", s.string(), "-o", out.string(), "--no-dispersion", "--quiet"});
    };
    REQUIRE(compare(timed, d / "cmp_timed").code == 0);
    REQUIRE(compare(scene, d / "cmp").code == 0);
    const json a = summary(d / "cmp_timed"), b = summary(d / "cmp");
    REQUIRE(a["pulses"].size() == b["pulses"].size());
    for (std::size_t k = 0; k < a["pulses"].size(); ++k)
      CHECK(b["pulses"][k]["peak_ratio"].get<double>() ==
            Approx(a["pulses"][k]["peak_ratio"].get<double>()).epsilon(kSameRecord));
  }
  SECTION("without a time base, the refusal names the option") {
    const auto scene = classic_reading(d, "s.json", d / "channels.csv", nullptr);
    check_refused(process(scene, d / "out"), {"channels.csv", "measurement.time.interval"});
  }
}

TEST_CASE("A Yokogawa ASCII export is read on its HResolution and HOffset header",
          "[app][process][timebase]") {
  // Yokogawa's ASCII data file: sample i at HOffset + i·HResolution; the key column of the header
  // rows is empty in the data rows, and TraceName names the traces above their samples.
  const fs::path d = scratch_dir("timebase_yokogawa");
  const auto rec = simulated(d);
  const fs::path timed =
      classic_reading(d, "timed.json", d / "sim/gauges.csv", {{"column", "time_s"}, {"unit", "s"}});
  processed(timed, d / "timed");
  const std::string n = std::to_string(rec[0].size());
  const std::string header =
      "HeaderSize,16\nModel,DL850\nComment,\nBlockNumber,1\n"
      "TraceName,CH1,CH2\nBlockSize," +
      n + "," + n +
      "\nVUnit,V,V\nSampleRate,10MS/s,10MS/s\n"
      "HResolution,1.0000E-07,1.0000E-07\n"
      "HOffset,-2.0000E-05,-2.0000E-05\nHUnit,s,s\nDisplayBlockSize," +
      n + "," + n +
      "\nDisplayPointNo.,1,1\nDate,2024/05/02,2024/05/02\n"
      "Time,10:11:12.000,10:11:12.000\n";
  std::ofstream(d / "yokogawa.csv") << channels_only(rec, header, ",");
  SECTION("read on the header, said in a warning naming its rows") {
    const auto scene = classic_reading(d, "s.json", d / "yokogawa.csv", nullptr, "CH1", "CH2");
    processed(scene, d / "out");
    check_same_curve(d / "timed", d / "out", -20e-6);
    CHECK(has_warning(summary(d / "out"), "line 9 (HResolution)"));
    CHECK(has_warning(summary(d / "out"), "line 10 (HOffset)"));
  }
  SECTION("an interval the header agrees with: read, nothing said") {
    const auto scene = classic_reading(d, "s.json", d / "yokogawa.csv",
                                       {{"interval", "0.1 us"}, {"start", "-20 us"}}, "CH1", "CH2");
    processed(scene, d / "out");
    check_same_curve(d / "timed", d / "out", -20e-6);
    CHECK_FALSE(has_warning(summary(d / "out"), "HResolution"));
  }
  SECTION("an interval the header disagrees with: refused naming the header row") {
    const auto scene =
        classic_reading(d, "s.json", d / "yokogawa.csv", {{"interval", "0.2 us"}}, "CH1", "CH2");
    check_refused(process(scene, d / "out"),
                  {"yokogawa.csv", "line 9 (HResolution)", "measurement.time.interval"});
    check_refused(run_shpb({"validate", scene.string()}),
                  {"yokogawa.csv", "line 9 (HResolution)", "measurement.time.interval"});
  }
  SECTION("saved with its time column: the column is the time base") {
    std::ostringstream s;
    s.precision(17);
    s << header;
    for (std::size_t i = 0; i < rec[0].size(); ++i)
      s << -20e-6 + rec[0][i] << "," << rec[1][i] << "," << rec[2][i] << "\n";
    std::ofstream(d / "yokogawa.csv") << s.str();
    const auto scene = classic_reading(d, "s.json", d / "yokogawa.csv", nullptr, "CH1", "CH2");
    processed(scene, d / "out");
    CHECK_FALSE(has_warning(summary(d / "out"), "HResolution"));
    check_same_curve(d / "timed", d / "out", -20e-6);
  }
}

TEST_CASE("LabVIEW's Delta_X is not read: a .lvm without a time column names the row",
          "[app][process][timebase]") {
  // X0 may be an absolute time and each segment has its own header: the scene states the base.
  const fs::path d = scratch_dir("timebase_lvm");
  const std::string header =
      "LabVIEW Measurement\t\nWriter_Version\t2\nReader_Version\t2\nSeparator\tTab\n"
      "Decimal_Separator\t.\nMulti_Headings\tNo\nX_Columns\tNo\nTime_Pref\tRelative\n"
      "***End_of_Header***\t\n\t\nChannels\t2\t\nSamples\t8000\t8000\n"
      "X_Dimension\tTime\tTime\nX0\t0.0000000000000000E+0\t0.0000000000000000E+0\n"
      "Delta_X\t1.000000E-7\t1.000000E-7\n***End_of_Header***\t\t\nincident\ttransmitted\n";
  const shpb_test::Record r;
  std::ostringstream s;
  s.precision(17);
  s << header;
  for (int i = 0; i < shpb_test::kSamples; ++i)
    s << r.incident_gauge(i * shpb_test::kDt) << "\t" << r.transmitted_gauge(i * shpb_test::kDt)
      << "\n";
  std::ofstream(d / "record.lvm") << s.str();
  json scene = shpb_test::steel_scene();
  scene["measurement"]["file"] = "record.lvm";
  scene["measurement"].erase("time");
  std::ofstream(d / "scene.json") << scene.dump(2);
  check_refused(process(d / "scene.json", d / "out"),
                {"record.lvm", "line 15 (Delta_X)", "measurement.time.interval"});
  scene["measurement"]["time"] = {{"interval", "0.1 us"}};
  std::ofstream(d / "scene.json") << scene.dump(2);
  const auto ok = process(d / "scene.json", d / "out");
  INFO(ok.err);
  CHECK(ok.code == 0);
}

TEST_CASE("An .xls workbook is read on the scene's interval, its time column left unread",
          "[app][process][timebase][excel]") {
  // tests/data/signals.xls: the clean record of lab_record.hpp at 1 MHz (800 samples) beside its
  // time column, doubles computed by Perl from the same formula as the CSV's, equal to the last
  // bit or two.
  constexpr double kSameDoubles = 1e-12;
  const fs::path d = scratch_dir("timebase_xls");
  const double dt = 1e-6;
  json scene = shpb_test::steel_scene();
  shpb_test::write(d, scene, shpb_test::csv(shpb_test::clean(), 1.0, dt, 800));
  processed(d / "scene.json", d / "csv");
  fs::copy_file(kSource / "tests/data/signals.xls", d / "signals.xls");
  scene["measurement"]["file"] = "signals.xls";
  scene["measurement"]["sheet"] = "signals";
  scene["measurement"]["time"] = {{"interval", "1 us"}};
  std::ofstream(d / "scene.json") << scene.dump(2);
  processed(d / "scene.json", d / "xls");
  const json ref = summary(d / "csv"), s = summary(d / "xls");
  for (const char* key : {"peak_stress_Pa", "max_strain"})
    CHECK(s[key].get<double>() == Approx(ref[key].get<double>()).epsilon(kSameDoubles));
  CHECK(s["windows"] == ref["windows"]);
}

TEST_CASE("A Yokogawa header without one usable time base is refused naming its row",
          "[app][process][timebase]") {
  const fs::path d = scratch_dir("timebase_yokogawa_bad");
  const shpb_test::Record r;
  json scene = shpb_test::steel_scene();
  scene["measurement"]["file"] = "yokogawa.csv";
  scene["measurement"].erase("time");
  scene["measurement"]["channels"][0]["column"] = "CH1";
  scene["measurement"]["channels"][1]["column"] = "CH2";
  std::ofstream(d / "scene.json") << scene.dump(2);
  const auto refused = [&](const std::string& rows, const std::vector<std::string>& said) {
    std::ostringstream s;
    s.precision(17);
    s << "Model,DL850\nTraceName,CH1,CH2\n" << rows << "Time,10:11:12.000,10:11:12.000\n";
    for (int i = 0; i < shpb_test::kSamples; ++i)
      s << "," << r.incident_gauge(i * shpb_test::kDt) << ","
        << r.transmitted_gauge(i * shpb_test::kDt) << "\n";
    std::ofstream(d / "yokogawa.csv") << s.str();
    CAPTURE(rows);
    check_refused(process(d / "scene.json", d / "out"), said);
  };
  // Traces of one file at two sample rates: no one time base.
  refused("HResolution,1.0000E-07,2.0000E-07\nHOffset,0,0\n",
          {"yokogawa.csv", "line 3 (HResolution)", "one time base"});
  // HUnit Hz: a spectrum's axis, not a record of time.
  refused("HResolution,1.0000E-07,1.0000E-07\nHOffset,0,0\nHUnit,Hz,Hz\n",
          {"yokogawa.csv", "line 5 (HUnit)", "expected a time unit"});
  refused("HResolution,0,0\nHOffset,0,0\n",
          {"yokogawa.csv", "line 3 (HResolution)", "expected a sample interval > 0"});
  refused("HResolution,1.0000E-07,1.0000E-07\nHOffset,soon,soon\n",
          {"yokogawa.csv", "line 4, column 2", "\"soon\""});
}

TEST_CASE("A time base given twice, or out of range, is refused naming its JSON path",
          "[app][validate][timebase]") {
  const fs::path d = scratch_dir("timebase_refusals");
  json scene = shpb_test::steel_scene();
  const std::string text = shpb_test::csv(shpb_test::Record{});
  shpb_test::write(d, scene, text);
  std::ofstream(d / "signals.raw") << text;
  const auto refused = [&](const json& time, const std::vector<std::string>& said,
                           const std::string& file = "signals.csv",
                           const std::string& format = "") {
    json s = scene;
    s["measurement"]["time"] = time;
    s["measurement"]["file"] = file;
    if (!format.empty()) s["measurement"]["format"] = format;
    std::ofstream(d / "scene.json") << s.dump(2);
    for (const char* command : {"validate", "process"}) {
      CAPTURE(command, time.dump(), file, format);
      check_refused(command == std::string("process")
                        ? process(d / "scene.json", d / "out")
                        : run_shpb({command, (d / "scene.json").string()}),
                    said);
    }
  };
  const std::string interval = "measurement.time.interval";
  refused({{"interval", "0.1 us"}, {"column", "time_s"}}, {interval, "measurement.time.column"});
  refused({{"interval", "0.1 us"}, {"unit", "s"}}, {interval, "measurement.time.unit"});
  refused({{"interval", "0.1 us"}, {"resample", true}}, {interval, "measurement.time.resample"});
  refused({{"interval", "0.1 us"}, {"rate", "10 MHz"}}, {"measurement.time.rate", "not both"});
  refused({{"interval", "10 MHz"}}, {interval, "expected a time"});
  refused({{"interval", "1 ms"}}, {interval, "must be in [1e-12, 1e-04]"});
  refused({{"interval", 1e-13}}, {interval, "must be in [1e-12, 1e-04]"});
  refused({{"rate", "1 kHz"}}, {"measurement.time.rate", "must be in"});
  refused({{"start", "-20 us"}}, {"measurement.time.start", interval});
  refused({{"interval", "0.1 us"}}, {"signals.raw", interval, "own time base"}, "signals.raw");
  refused({{"interval", "0.1 us"}}, {"signals.csv", interval, "own time base"}, "signals.csv",
          "tektronix");
}

}  // namespace tests_app_test_record_time_base
