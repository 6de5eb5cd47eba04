
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <tuple>

#include "../app/write_xlsx.hpp"
#include "../scratch.hpp"
#include "analysis/gauge_signals.hpp"
#include "core/error.hpp"
#include "core/signal_reader.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_core_test_signal_reader {

using namespace shpb;
namespace fs = std::filesystem;

namespace {

// The folder of this test process, removed when the process ends.
const shpb_test::ScratchDir scratch("signal_reader");

fs::path write_file(const std::string& name, const std::string& bytes) {
  const fs::path p = scratch.path() / name;
  std::ofstream(p, std::ios::binary) << bytes;
  return p;
}

ColumnRef by_name(const std::string& n) { return {n, std::nullopt}; }
ColumnRef by_index(int i) { return {"", i}; }

SignalRequest csv_request(const fs::path& p, std::vector<ColumnRef> cols) {
  SignalRequest r;
  r.file = p;
  r.columns = std::move(cols);
  return r;
}

// The message of the InputError thrown by f ("" if none).
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// The request refused as a channel header's rows of numbers, the message holding `error`.
void check_header_rows_refused(const SignalRequest& r, const std::string& error) {
  const std::string e = error_of([&] { read_signal_columns(r); });
  CHECK(e.find(error) != std::string::npos);
  CHECK(e.find("export without the channel header") != std::string::npos);
}

// The measured records ship with their experiments (experiments/<name>/data, each with its
// LICENSE).
const fs::path kExperiments = fs::path(SHPB_SOURCE_DIR) / "experiments";

}  // namespace

TEST_CASE("A CSV file with metadata lines is read by column name and index", "[core][signal]") {
  const auto p = write_file("plain.csv",
                            "Scope export\r\nDate,2024-01-01\r\nTime/s,ch1 (V),ch2 (V)\r\n"
                            "0,0.5,-1\r\n1e-6,0.25,-2\r\n2e-6,0,-3\r\n");
  auto r = csv_request(p, {by_name("ch2 (V)"), by_index(1)});
  r.time_column = by_name("Time/s");
  const SignalColumns s = read_signal_columns(r);
  REQUIRE(s.time_s.size() == 3);
  CHECK(s.dt_s == Approx(1e-6));
  CHECK(s.values[0] == std::vector<double>{-1, -2, -3});
  CHECK(s.values[1] == std::vector<double>{0.5, 0.25, 0});
  CHECK(s.names[0] == "ch2 (V)");
  CHECK(s.warnings.empty());
}

TEST_CASE("Columns are named by the row above a row of units", "[core][signal]") {
  // PicoScope writes the names, then their units, then a blank line; Keysight "x-axis,1,2" over
  // "second,Volt,Volt". The units row is the header the data rows follow; the names are above.
  const auto pico = write_file("pico.csv",
                               "Time,Channel A,Channel B\r\n(ms),(mV),(mV)\r\n\r\n"
                               "-0.0001,1.5,-2\r\n0.0000,2.5,-3\r\n0.0001,3.5,-4\r\n");
  auto r = csv_request(pico, {by_name("Channel B"), by_name("channel a")});
  r.time_column = by_name("Time");
  r.time_unit_s = 1e-3;
  const SignalColumns s = read_signal_columns(r);
  CHECK(s.values[0] == std::vector<double>{-2, -3, -4});
  CHECK(s.values[1] == std::vector<double>{1.5, 2.5, 3.5});
  CHECK(s.names[0] == "Channel B");
  CHECK(s.time_s.front() == Approx(-1e-7));
  // A name the names row lacks is refused with the names listed.
  r.columns = {by_name("Channel C")};
  CHECK(error_of([&] { read_signal_columns(r); })
            .find("pico.csv: line 1: column \"Channel C\": no such column; the header has "
                  "\"Time\", \"Channel A\", \"Channel B\"") != std::string::npos);
  const auto keysight =
      write_file("scope_1.csv", "x-axis,1,2\nsecond,Volt,Volt\n-1e-7,0.5,1\n0,0.25,2\n1e-7,0,3\n");
  CHECK(read_signal_columns(csv_request(keysight, {by_name("2")})).values[0] ==
        std::vector<double>{1, 2, 3});
  // A unit that names one column alone still names it.
  const auto single =
      write_file("single.csv", "x-axis,1\nsecond,Volt\n-1e-7,0.5\n0,0.25\n1e-7,0\n");
  CHECK(read_signal_columns(csv_request(single, {by_name("Volt")})).values[0] ==
        std::vector<double>{0.5, 0.25, 0});
}

TEST_CASE("A workbook formula is read by the value it holds, and named when it holds none",
          "[core][signal][excel]") {
  // Spreadsheet programs store a formula's value beside it; programs that write workbooks
  // without computing formulas (e.g. Python's openpyxl) store the formula alone.
  const auto workbook = [](const std::string& time_cell) {
    const fs::path p = scratch.path() / "formula.xlsx";
    std::vector<std::string> shared{"t", "v"};
    shpb_test::write_zip(
        p,
        shpb_test::xlsx_parts("<row r=\"1\"><c r=\"A1\" t=\"s\"><v>0</v></c>"
                              "<c r=\"B1\" t=\"s\"><v>1</v></c></row>"
                              "<row r=\"2\"><c r=\"A2\"><v>0</v></c><c r=\"B2\"><v>1</v></c></row>"
                              "<row r=\"3\">" +
                                  time_cell +
                                  "<c r=\"B3\"><v>2</v></c></row>"
                                  "<row r=\"4\"><c r=\"A4\"><v>2E-6</v></c><c r=\"B4\"><v>3</v>"
                                  "</c></row>",
                              shared));
    auto r = csv_request(p, {by_name("v")});
    r.sheet = "signals";
    return r;
  };
  const SignalColumns s =
      read_signal_columns(workbook("<c r=\"A3\"><f>A2+1E-6</f><v>1E-6</v></c>"));
  CHECK(s.time_s == std::vector<double>{0, 1e-6, 2e-6});
  const std::string error =
      error_of([&] { read_signal_columns(workbook("<c r=\"A3\"><f>A2+1E-6</f></c>")); });
  INFO(error);
  CHECK(error.find("formula.xlsx: line 3, column 1 (\"t\"): \"=A2+1E-6\": a formula whose value "
                   "the workbook does not hold") != std::string::npos);
  // An .xls holds the value too, but its reader (FreeXL) gives none: the cell reads empty, and
  // the message says what it may be (tests/data/make_formula_xls.pl).
  auto xls = csv_request(fs::path(SHPB_SOURCE_DIR) / "tests/data/formula.xls", {by_name("v")});
  xls.sheet = "signals";
  const std::string xls_error = error_of([&] { read_signal_columns(xls); });
  INFO(xls_error);
  CHECK(xls_error.find("formula.xls: line 3, column 1 (\"t\"): empty field: expected a number (the "
                       ".xls reader gives no formula's value") != std::string::npos);
}

TEST_CASE("Workbook text cells with decimal commas are read as numbers", "[core][signal][excel]") {
  // A German CSV pasted into a spreadsheet of another locale leaves its numbers as text cells.
  const auto cell = [](const std::string& ref, const std::string& text) {
    return "<c r=\"" + ref + "\" t=\"inlineStr\"><is><t>" + text + "</t></is></c>";
  };
  std::string rows = "<row r=\"1\">" + cell("A1", "Zeit") + cell("B1", "DMS") + "</row>";
  const char* samples[][2] = {{"0,000000", "0,5"}, {"0,000001", "1,5E-03"}, {"0,000002", "-2,25"}};
  for (int i = 0; i < 3; ++i) {
    const std::string r = std::to_string(i + 2);
    rows += "<row r=\"" + r + "\">" + cell("A" + r, samples[i][0]) + cell("B" + r, samples[i][1]) +
            "</row>";
  }
  const fs::path p = scratch.path() / "text_cells.xlsx";
  shpb_test::write_zip(p, shpb_test::xlsx_parts(rows, {}));
  auto r = csv_request(p, {by_name("DMS")});
  r.sheet = "signals";
  const SignalColumns s = read_signal_columns(r);
  CHECK(s.values[0] == std::vector<double>{0.5, 1.5e-3, -2.25});
  CHECK(s.dt_s == Approx(1e-6));
}

TEST_CASE("Semicolon and tab files with decimal commas are detected", "[core][signal]") {
  SECTION("semicolon") {
    const auto p = write_file("semi.csv", "t [ms];eps\n0,000;1,5\n0,001;2,5E-03\n0,002;-3,0\n");
    auto r = csv_request(p, {by_name("eps")});
    r.time_unit_s = 1e-3;
    const auto s = read_signal_columns(r);
    CHECK(s.values[0][1] == Approx(2.5e-3));
    CHECK(s.dt_s == Approx(1e-6));
  }
  SECTION("a point where the decimal mark is the comma is refused, never read as a decimal") {
    // German spreadsheets write the thousands with a point: "1.140" µε is 1140, not 1.14.
    const auto p = write_file("thousands.csv",
                              "Zeit [ms];inc [\xb5\xce\xb5]\n0,0000;0\n0,0001;987\n0,0002;1.140\n"
                              "0,0003;-5\n");
    auto r = csv_request(p, {by_index(1)});
    r.time_unit_s = 1e-3;
    const std::string error = error_of([&] { read_signal_columns(r); });
    INFO(error);
    CHECK(error.find(
              "thousands.csv: line 4, column 2 (\"inc [\xc2\xb5\xce\xb5]\"): \"1.140\": a point in "
              "a file whose decimal mark is the comma: a thousands separator") !=
          std::string::npos);
    // The other way round, "1,012" in a file of decimal points.
    const auto q = write_file("thousands.tsv", "t\tinc\n0.0000\t987\n0.0001\t1,012\n0.0002\t5\n");
    r = csv_request(q, {by_index(1)});
    r.time_unit_s = 1e-3;
    CHECK(error_of([&] { read_signal_columns(r); })
              .find("thousands.tsv: line 3, column 2 (\"inc\"): \"1,012\": a comma in a file "
                    "whose decimal mark is the point") != std::string::npos);
  }
  SECTION("comma-separated, decimal commas in quoted fields") {
    // pandas' to_csv(decimal=",") and LibreOffice quote a field holding the separator.
    const auto p =
        write_file("quoted.csv", "t,eps\n\"-0,0001\",0\n0,\"1,5E-03\"\n\"0,0001\",\"-2,25\"\n");
    const auto s = read_signal_columns(csv_request(p, {by_name("eps")}));
    CHECK(s.values[0] == std::vector<double>{0, 1.5e-3, -2.25});
    CHECK(s.time_s == std::vector<double>{-1e-4, 0, 1e-4});
    // English spreadsheets quote thousands the same way: "1,250" is no decimal comma.
    const auto q =
        write_file("quoted_thousands.csv", "t,eps\n0,\"1,250\"\n1,\"2,500\"\n2,\"3,750\"\n");
    auto r = csv_request(q, {by_name("eps")});
    r.time_unit_s = 1e-6;
    CHECK(error_of([&] { read_signal_columns(r); })
              .find("quoted_thousands.csv: line 4: no numeric rows: expected rows of numbers after "
                    "the header; line 4 was read as 2 field(s) separated by commas, decimal point: "
                    "\"3,750\": a comma in a file whose decimal mark is the point") !=
          std::string::npos);
  }
  SECTION("tab, Latin-1 header and footer") {
    // Quoted into a warning, a name or a message, Latin-1 text was written as its bytes, which
    // no JSON output takes (summary.json: exit 4, "invalid UTF-8 byte"): now as UTF-8.
    const auto p = write_file(
        "tab.tsv", "Zeit\tDehnung \xb5\xe9\n0\t1,25\n1\t2,5\n2\t3,75\nEnde (Messger\xe4t)\n");
    const auto s = read_signal_columns(csv_request(p, {by_index(1)}));
    CHECK(s.values[0] == std::vector<double>{1.25, 2.5, 3.75});
    CHECK(s.names[0] == "Dehnung \xc2\xb5\xc3\xa9");
    REQUIRE(s.warnings.size() == 1);
    CHECK(s.warnings[0].find("(a footer, \"Ende (Messger\xc3\xa4t)\")") != std::string::npos);
    const auto q = write_file("tab.tsv", "Zeit\tDehnung \xb5\xe9\n0\t1,25\n1\tzw\xf6lf\n");
    CHECK(error_of([&] {
            read_signal_columns(csv_request(q, {by_index(1)}));
          }).find("line 3, column 2 (\"Dehnung \xc2\xb5\xc3\xa9\"): \"zw\xc3\xb6lf\"") !=
          std::string::npos);
  }
}

TEST_CASE("Broken signal files are rejected naming file, line and column", "[core][signal]") {
  const std::string head = "time_s,incident,transmitted\n";
  SECTION("missing column") {
    const auto p = write_file("missing.csv", head + "0,1,2\n1,1,2\n");
    const auto msg = error_of([&] { read_signal_columns(csv_request(p, {by_name("reflected")})); });
    CHECK(msg.find("missing.csv") != std::string::npos);
    CHECK(msg.find("line 1") != std::string::npos);
    CHECK(msg.find("\"reflected\"") != std::string::npos);
    CHECK(msg.find("\"incident\"") != std::string::npos);  // lists what there is
  }
  SECTION("text in numbers") {
    const auto p = write_file("text.csv", head + "0,1,2\n1,1,2\n2,1O,2\n");
    const auto msg = error_of([&] { read_signal_columns(csv_request(p, {by_name("incident")})); });
    CHECK(msg.find("text.csv: line 4, column 2 (\"incident\"): \"1O\"") != std::string::npos);
  }
  SECTION("NaN") {
    const auto p = write_file("nan.csv", head + "0,1,2\n1,NaN,2\n2,1,2\n");
    const auto msg = error_of([&] { read_signal_columns(csv_request(p, {by_name("incident")})); });
    CHECK(msg.find("line 3, column 2") != std::string::npos);
    CHECK(msg.find("NaN") != std::string::npos);
  }
  SECTION("an instrument's overrange or not-a-number marker") {
    // SCPI scopes write IEEE 488.2's 9.9E37 (overrange) and 9.91E37 (not a number) as numbers.
    const auto p = write_file("scpi.csv", head + "0,1,2\n1,9.91E+37,2\n2,1,2\n3,1,-9.9E37\n");
    const auto msg = error_of([&] { read_signal_columns(csv_request(p, {by_name("incident")})); });
    CHECK(msg.find("scpi.csv: line 3, column 2 (\"incident\"): \"9.91E+37\": an instrument's "
                   "overrange or not-a-number marker") != std::string::npos);
    const auto low =
        error_of([&] { read_signal_columns(csv_request(p, {by_name("transmitted")})); });
    CHECK(low.find("scpi.csv: line 5, column 3") != std::string::npos);
  }
  SECTION("non-monotonic time") {
    const auto p = write_file("back.csv", head + "0,1,2\n2,1,2\n1,1,2\n3,1,2\n");
    const auto msg = error_of([&] { read_signal_columns(csv_request(p, {by_name("incident")})); });
    CHECK(msg.find("back.csv: line 4") != std::string::npos);
    CHECK(msg.find("backwards") != std::string::npos);
  }
  SECTION("truncated line") {
    const auto p = write_file("trunc.csv", head + "0,1,2\n1,1,2\n2,1");
    const auto msg =
        error_of([&] { read_signal_columns(csv_request(p, {by_name("transmitted")})); });
    CHECK(msg.find("trunc.csv: line 4, column 3") != std::string::npos);
    CHECK(msg.find("truncated") != std::string::npos);
  }
  SECTION("empty file") {
    const auto p = write_file("empty.csv", "");
    const auto msg = error_of([&] { read_signal_columns(csv_request(p, {by_index(1)})); });
    CHECK(msg.find("empty.csv: line 1") != std::string::npos);
  }
  SECTION("header only") {
    const auto p = write_file("header.csv", head);
    CHECK(error_of([&] {
            read_signal_columns(csv_request(p, {by_index(1)}));
          }).find("header.csv") != std::string::npos);
  }
  SECTION("digits grouped by thousands") {
    // Excel's "#,##0.000" in a German (point) or French (narrow no-break space) locale: named
    // as such, never read ("1.234" alone may be either mark).
    const std::string de = "t;v\n0,0;1,000\n1,0;999,500\n2,0;-1.197,266\n";
    const auto p = write_file("de.csv", de);
    CHECK(error_of([&] { read_signal_columns(csv_request(p, {by_name("v")})); })
              .find("de.csv: line 4, column 2 (\"v\"): \"-1.197,266\": digits grouped by "
                    "thousands (a point between them)") != std::string::npos);
    const auto fr = write_file("fr.csv",
                               "t;v\n0,0;1,000\n1,0;2\xE2\x80\xAF"
                               "500,125\n");
    CHECK(error_of([&] { read_signal_columns(csv_request(fr, {by_name("v")})); })
              .find("line 3, column 2 (\"v\"): \"2\xE2\x80\xAF"
                    "500,125\": digits grouped by "
                    "thousands (a narrow no-break space between them)") != std::string::npos);
  }
  SECTION("gap in the time base") {
    const auto p = write_file("gap.csv", head + "0,1,2\n1,1,2\n2,1,2\n5,1,2\n6,1,2\n");
    const auto msg = error_of([&] { read_signal_columns(csv_request(p, {by_index(1)})); });
    CHECK(msg.find("gap.csv: line 5") != std::string::npos);
  }
}

TEST_CASE("A data row with text in one field is a data row, never taken for the header",
          "[core][signal]") {
  // A scope writes "NaN", "OVER" or "∞" for a sample beyond its range; in the first rows such a
  // row, taken for the header, would drop its samples unseen or hide the real header.
  const std::string head = "time_s,incident,transmitted,trigger\n";
  const std::string rest = "2e-6,3,30,0\n3e-6,4,40,0\n";
  struct Case {
    const char* what;
    std::string file;
    ColumnRef time, column;
    std::string error;        // the refusal, or empty: read whole
    std::size_t samples = 0;  // ... with this many samples
  };
  const Case cases[] = {
      {"NaN in the first sample of a column read by index",
       head + "0,NaN,0,0\n1e-6,2,20,0\n" + rest,
       {},
       by_index(1),
       "first.csv: line 2, column 2 (\"incident\"): \"NaN\""},
      {"NaN in the first sample of a column read by name", head + "0,NaN,0,0\n1e-6,2,20,0\n" + rest,
       by_name("time_s"), by_name("incident"),
       "first.csv: line 2, column 2 (\"incident\"): \"NaN\""},
      {"OVER in the first samples of a column not read, by name",
       head + "0,1,10,OVER\n1e-6,2,20,OVER\n" + rest, by_name("time_s"), by_name("incident"), "",
       4},
      {"\u221e in the first samples of a column not read, by index, no header",
       "0,1,10,\u221e\n1e-6,2,20,\u221e\n" + rest,
       {},
       by_index(1),
       "",
       4},
      {"\u221e, -\u221e, NaN and #N/A in every sample of columns not read (a channel overranged "
       "throughout, one not recorded)",
       "time_s,incident,transmitted,trigger,temperature\n0,1,10,\u221e,NaN\n1e-6,2,20,-\u221e,#N/"
       "A\n"
       "2e-6,3,30,\u221e,NaN\n3e-6,4,40,\u221e,nan\n",
       by_name("time_s"), by_name("incident"), "", 4},
      {"a metadata line right above the data stays metadata",
       "Sample Interval,1e-6,s,V\n" + rest,
       {},
       by_index(1),
       "",
       2},
  };
  for (const auto& c : cases) {
    DYNAMIC_SECTION(c.what) {
      const auto p = write_file("first.csv", c.file);
      auto r = csv_request(p, {c.column});
      r.time_column = c.time;
      if (!c.error.empty()) {
        CHECK(error_of([&] { read_signal_columns(r); }).find(c.error) != std::string::npos);
      } else {
        const SignalColumns s = read_signal_columns(r);
        REQUIRE(s.time_s.size() == c.samples);
        CHECK(s.values[0].back() == 4);
        CHECK(s.time_s.front() == (c.samples == 4 ? 0 : 2e-6));
      }
    }
  }
}

TEST_CASE(
    "Rows of numbers between a channel header's names and its data are refused and never read",
    "[core][signal]") {
  // catman-style channel headers: under each column's name its sample rate and channel number
  // (rows of numbers only), sometimes above a row of units. Read as the first samples, a sample
  // rate of 1e7 or a channel number became a time and a strain; the message named a time going
  // backwards, or the units row's "s" as a bad sample.
  const std::string data =
      "-2e-6,0.5,-1\n-1e-6,0.5,-1\n0,0.5,-1\n1e-6,0.75,-2\n2e-6,1,-3\n"
      "3e-6,1.25,-4\n";
  struct Case {
    const char* what;
    std::string head;
    std::string error;  // the refusal, or empty: read whole
  };
  const Case cases[] = {
      {"sample rates and channel numbers under the names",
       "Time,incident,transmitted\n1000000,1000000,1000000\n0,1,2\n",
       "head.csv: line 2, column 1 (\"Time\"): \"1000000\": not on the clock of the samples below "
       "(every 1e-06 s from -2e-06 s at line 4): lines 2–3 under the header (line 1)"},
      {"a channel number under the names and units", "Time,incident,transmitted\ns,V,V\n0,1,2\n",
       "head.csv: line 3, column 1 (\"Time\"): \"0\": not on the clock of the samples below "
       "(every 1e-06 s from -2e-06 s at line 4): line 3 under the header (line 2)"},
      {"sample rates and channel numbers above the units",
       "Time,incident,transmitted\n1000000,1000000,1000000\n0,1,2\ns,V,V\n",
       "head.csv: line 4: \"s\": no number in this row, above the samples: lines 2–3 under the "
       "header (line 1)"},
      {"the names and units alone", "Time,incident,transmitted\ns,V,V\n", ""},
      {"samples whose first stamp is a step early on their clock",
       "Time,incident,transmitted\n-3e-6,0.5,-1\n", ""},
  };
  for (const auto& c : cases) {
    DYNAMIC_SECTION(c.what) {
      const auto p = write_file("head.csv", c.head + data);
      auto r = csv_request(p, {by_name("incident")});
      r.time_column = by_name("Time");
      if (!c.error.empty()) {
        check_header_rows_refused(r, c.error);
      } else {
        const SignalColumns s = read_signal_columns(r);
        CHECK(s.values[0].back() == 1.25);
        CHECK(s.dt_s == Approx(1e-6));
      }
    }
  }
  SECTION("under a row of comments the time column by index still shows them") {
    // The row above the first row of numbers was taken for the header: "no such column".
    const auto p = write_file("head.csv",
                              "Time,incident,transmitted\nComment,bar 1,bar 2\n"
                              "1000000,1000000,1000000\n0,1,2\n" +
                                  data);
    const std::string e =
        error_of([&] { read_signal_columns(csv_request(p, {by_name("incident")})); });
    CHECK(e.find("head.csv: line 3, column 1 (\"Comment\"): \"1000000\": not on the clock") !=
          std::string::npos);
    CHECK(e.find("lines 3–4 under the header (line 2)") != std::string::npos);
  }
  SECTION("without a time column, a row of units below them still shows them") {
    const auto p = write_file("head.csv",
                              "incident,transmitted\n1000000,1000000\n0,1\nV,V\n"
                              "0.5,-1\n0.5,-1\n0.75,-2\n");
    auto r = csv_request(p, {by_name("incident")});
    r.clock = SampleClock{1e-6, 0};
    CHECK(error_of([&] {
            read_signal_columns(r);
          }).find("line 4: \"V\": no number in this row, above the samples: lines 2–3") !=
          std::string::npos);
  }
}

TEST_CASE(
    "Rows of numbers under the names of a file without a time column are judged by the samples "
    "below",
    "[core][signal]") {
  // measurement.time.interval: no clock to judge a channel header's rows by, and a sample rate, a
  // sample count or a channel number under the names was read as the first sample of each channel
  // (then refused as an implausible strain or a pulse at the record's start, or read as a spike).
  // A record's first samples are its rest: a row off their level, or written in another form than
  // the whole column below it, is no sample of theirs.
  const auto quiet = [](int rows, const char* format, double a, double b) {
    std::string text;
    char line[64];
    for (int i = 0; i < rows; ++i) {
      // rest ± a few steps (0.01 and 0.02), the same pattern every 5 rows
      std::snprintf(line, sizeof line, format, a + 0.01 * ((i * 3) % 5 - 2),
                    b + 0.02 * ((i * 2) % 5 - 2));
      text += line;
    }
    return text;
  };
  std::string one_level;
  for (int i = 0; i < 20; ++i) one_level += "0.50,1\n";
  struct Case {
    const char* what;
    std::string text;
    std::string error;  // the refusal, or empty: read whole, the first sample `first`
    double first = 0;
  };
  const Case cases[] = {
      {"sample rates and channel numbers",
       "incident,transmitted\n1000000,1000000\n1,2\n" + quiet(40, "%.4f,%.4f\n", 0.5, -0.3),
       "head.csv: line 2, column 1 (\"incident\"): \"1000000\": off the level of the samples "
       "below"},
      {"a channel number on the rest level, written unlike the column",
       "incident,transmitted\n0,1\n" + quiet(40, "%.3f,%.3f\n", 0.0, 1.0),
       "head.csv: line 2, column 1 (\"incident\"): \"0\": written with 0 decimals where every "
       "value below it in the column has 3 decimals (lines 3–42): line 2 under the header"},
      {"samples in %g", "incident,transmitted\n" + quiet(40, "%g,%g\n", 0.0, 1.0), "", -0.02},
      {"a first sample two of the column's steps off a level the next 20 all read",
       "incident,transmitted\n0.52,1\n" + one_level + quiet(40, "%.2f,%.0f\n", 0.5, 1), "", 0.52},
  };
  for (const auto& c : cases) {
    DYNAMIC_SECTION(c.what) {
      const auto p = write_file("head.csv", c.text);
      auto r = csv_request(p, {by_name("incident")});
      r.clock = SampleClock{1e-6, 0};
      if (!c.error.empty()) {
        check_header_rows_refused(r, c.error);
      } else {
        const SignalColumns s = read_signal_columns(r);
        CHECK(s.values[0].front() == Approx(c.first));
        CHECK(s.warnings.empty());
      }
    }
  }
}

TEST_CASE("A sample count alone on the first line is the header's when it counts the samples",
          "[core][signal]") {
  // Scope exports that write the number of points first: the count was refused as a header row
  // of numbers. It is the header's when it is the number of samples below it; another number
  // above rows of several fields is refused as a count that does not match them.
  std::string rows;
  for (int i = 0; i < 30; ++i) rows += std::to_string(i) + "e-6," + std::to_string(i % 3) + "\n";
  SECTION("above the names") {
    const auto p = write_file("count.csv", "30\nTime,incident\n" + rows);
    const SignalColumns s = read_signal_columns(csv_request(p, {by_name("incident")}));
    REQUIRE(s.values[0].size() == 30);
    CHECK(s.values[0][1] == 1);
    REQUIRE(s.warnings.size() == 1);
    CHECK(s.warnings[0].find("line 1 holds 30 alone, the number of samples below it (lines "
                             "3–32): read as the header's sample count") != std::string::npos);
  }
  SECTION("right above the samples") {
    const auto p = write_file("count.csv", "30\n" + rows);
    const SignalColumns s = read_signal_columns(csv_request(p, {by_index(1)}));
    CHECK(s.values[0].size() == 30);
    CHECK(s.time_s.front() == 0);
  }
  SECTION("a count that is not the samples'") {
    const auto p = write_file("count.csv", "31\nTime,incident\n" + rows);
    CHECK(error_of([&] { read_signal_columns(csv_request(p, {by_name("incident")})); })
              .find("count.csv: line 1: \"31\": a number alone on its line above rows of 2 "
                    "fields: a header's sample count, but lines 3–32 hold 30 samples") !=
          std::string::npos);
  }
}

TEST_CASE("Fortran's D exponents are read as the E they mean", "[core][signal]") {
  // DOUBLE PRECISION values as Fortran writes them ("0.1000000000000000D-05", list-directed or
  // with a D edit descriptor): refused as "expected a finite number" before.
  const auto p = write_file("fortran.txt",
                            " t_s incident transmitted\n"
                            " 0.0000000000000000D+00 -0.1250000000000000D-03 0.5D0\n"
                            " 0.1000000000000000D-05 -0.2500000000000000D-03 0.25d+1\n"
                            " 0.2000000000000000D-05 -0.3750000000000000D-03 -0.75D-2\n");
  auto r = csv_request(p, {by_name("incident"), by_name("transmitted")});
  r.time_column = by_name("t_s");
  const SignalColumns s = read_signal_columns(r);
  CHECK(s.time_s == std::vector<double>{0, 1e-6, 2e-6});
  CHECK(s.values[0] == std::vector<double>{-0.125e-3, -0.25e-3, -0.375e-3});
  CHECK(s.values[1] == std::vector<double>{0.5, 2.5, -0.75e-2});
  SECTION("with decimal commas") {
    const auto q =
        write_file("fortran.txt", "t_s;x\n0,0D+00;-0,125D-03\n0,1D-05;0,25d+1\n0,2D-05;-0,75D-2\n");
    auto rq = csv_request(q, {by_name("x")});
    rq.time_column = by_name("t_s");
    const SignalColumns c = read_signal_columns(rq);
    CHECK(c.time_s == std::vector<double>{0, 1e-6, 2e-6});
    CHECK(c.values[0] == std::vector<double>{-0.125e-3, 2.5, -0.75e-2});
  }
  SECTION("a D that is no exponent stays text") {
    // No decimal point before it, no digits after it, or more than three: names, not numbers.
    for (const char* field : {"3D4", "2d", "1.5D", "1.5D+", "1.5D1234", "D-03", "1.5.2D3"}) {
      const auto q =
          write_file("fortran.txt", std::string("t_s,x\n0,") + field + "\n1e-6,1\n2e-6,2\n");
      auto rq = csv_request(q, {by_name("x")});
      rq.time_column = by_name("t_s");
      CHECK(error_of([&] {
              read_signal_columns(rq);
            }).find(std::string("line 2, column 2 (\"x\"): \"") + field + "\"") !=
            std::string::npos);
    }
  }
}

TEST_CASE("A time unit the header gives must be the one the column is read in", "[core][signal]") {
  // Scopes and spreadsheets name the unit in the header ("Time (ms)", "t [us]", "Time/s"), or in
  // a unit row below it (PicoScope "(ms)", Keysight "second"); a name without one says nothing.
  struct Case {
    std::string head;
    double unit_s;  // seconds per unit the column is read in
    bool refused;
  };
  const Case cases[] = {
      {"Time (ms),v", 1, true},
      {"Time (ms),v", 1e-3, false},
      {"t [us],v", 1e-6, false},
      {"Zeit [\xb5s],v", 1e-6, false},
      {"t [\xc2\xb5s],v", 1, true},
      {"Time/s,v", 1e-6, true},
      {"time_s,v", 1, false},
      {"Time,v\n(ms),(V)", 1, true},
      {"x-axis,1\nsecond,Volt", 1, false},
      {"Time,v", 1e-3, false},
      {"Sample,v", 1e-6, false},
      {"time_index,v", 1e-6, false},
  };
  for (const auto& c : cases) {
    DYNAMIC_SECTION(c.head << " read in " << c.unit_s << " s") {
      const auto p = write_file("unit.csv", c.head + "\n0,1\n1,2\n2,3\n");
      auto r = csv_request(p, {by_index(1)});
      r.time_unit_s = c.unit_s;
      const std::string error = error_of([&] { read_signal_columns(r); });
      INFO(error);
      CHECK((error.find("the header gives the time in") != std::string::npos) == c.refused);
      if (c.refused) CHECK(error.find("unit.csv: line ") != std::string::npos);
    }
  }
}

TEST_CASE("Names are refused where the data rows hold more columns than the header names",
          "[core][signal]") {
  // Decimal commas in a comma-separated file: "-990,5" is two fields, and "incident" would land
  // on the integer part of the incident strain and "transmitted" on its decimals.
  const std::string split =
      "time_ns,incident,transmitted\n0,0,0\n200,-990,5,-3,25\n"
      "400,-1001,5,-4,5\n600,-998,75,-5,125\n";
  auto r = csv_request(write_file("split.csv", split), {by_name("transmitted")});
  r.time_unit_s = 1e-9;
  const std::string error = error_of([&] { read_signal_columns(r); });
  CHECK(error.find("split.csv: line 1: column \"transmitted\": the header names 3 columns but "
                   "line 3 holds 5") != std::string::npos);
  // By index, the same split file is refused at its first split number: index 2 would read the
  // decimals of the incident strain, and times in µs written "-200,5" pass for rounded stamps.
  auto by_position = csv_request(write_file("split.csv", split), {by_index(2)});
  by_position.time_unit_s = 1e-9;
  const std::string by_index_error = error_of([&] { read_signal_columns(by_position); });
  INFO(by_index_error);
  CHECK(by_index_error.find("split.csv: line 3: \"-990,5\": a number with a decimal comma in a "
                            "comma-separated file") != std::string::npos);
  auto rounded = csv_request(write_file("split_us.csv",
                                        "t_us,incident,transmitted\n"
                                        "-200,0,1,5E-04,2,5E-05\n"
                                        "-199,9,1,6E-04,2,6E-05\n"
                                        "-199,8,1,7E-04,2,7E-05\n"),
                             {by_index(1), by_index(2)});
  rounded.time_unit_s = 1e-6;
  CHECK(error_of([&] {
          read_signal_columns(rounded);
        }).find("split_us.csv: line 2: \"-200,0\": a number with a decimal comma") !=
        std::string::npos);
  // Numbers with decimal points under a shorter metadata line are read by index as before.
  const auto metadata = write_file("metadata.csv",
                                   "Sample interval,1e-7\n0,0.5,0.25\n"
                                   "1e-7,1.5,1.25\n2e-7,2.5,2.25\n");
  CHECK(read_signal_columns(csv_request(metadata, {by_index(2)})).values[0] ==
        std::vector<double>{0.25, 1.25, 2.25});
  // A trailing separator adds no column.
  const auto trailing = write_file("trailing.csv", "t,a,b\n0,1,2,\n1,3,4,\n2,5,6,\n");
  CHECK(read_signal_columns(csv_request(trailing, {by_name("b")})).values[0] ==
        std::vector<double>{2, 4, 6});
}

TEST_CASE("A long record is read whole and its first bad field named, whichever half it is in",
          "[core][signal]") {
  // 300 000 rows: parsed in two halves at once (signal_csv.cpp); the values land in order.
  constexpr int kRows = 300000;
  const auto record = [&](int bad_a, int bad_b) {
    std::string text = "time_s,incident\n";
    for (int i = 0; i < kRows; ++i)
      text += std::to_string(i) + "e-7," +
              (i == bad_a || i == bad_b ? std::string("x") : std::to_string(i % 97)) + "\n";
    return text;
  };
  const auto p = write_file("long.csv", record(-1, -1));
  const auto s = read_signal_columns(csv_request(p, {by_name("incident")}));
  REQUIRE(s.values[0].size() == static_cast<std::size_t>(kRows));
  bool in_order = true;
  for (int i = 0; i < kRows; ++i) in_order = in_order && s.values[0][i] == i % 97;
  CHECK(in_order);
  // Bad fields in both halves: the first one (data row 1000 is line 1002) is named.
  const auto both = write_file("long_bad.csv", record(1000, 250000));
  const auto msg = error_of([&] { read_signal_columns(csv_request(both, {by_name("incident")})); });
  CHECK(msg.find("line 1002") != std::string::npos);
  const auto late = write_file("long_late.csv", record(-1, 250000));
  const auto msg2 =
      error_of([&] { read_signal_columns(csv_request(late, {by_name("incident")})); });
  CHECK(msg2.find("line 250002") != std::string::npos);
}

TEST_CASE("Repeated time stamps are detected and the time base rebuilt with a warning",
          "[core][signal]") {
  // 1 µs stamps rounded from an 80 ns clock, as in the epoxy file.
  std::string text = "Time/s,a\n";
  for (int i = 0; i < 2000; ++i) {
    const double t = -1.98e-4 + i * 8e-8;
    char line[64];
    std::snprintf(line, sizeof line, "%.2E,%d\n", t, i);
    text += line;
  }
  const auto p = write_file("rounded.csv", text);
  const auto s = read_signal_columns(csv_request(p, {by_index(1)}));
  REQUIRE(s.warnings.size() == 1);
  CHECK(s.warnings[0].find("repeat") != std::string::npos);
  CHECK(s.dt_s == Approx(8e-8).epsilon(1e-12));
  // Rounding to 1 µs leaves the start uncertain by half a stamp.
  CHECK(std::abs(s.time_s[0] - -1.98e-4) < 1e-6);
}

TEST_CASE("A peak-detect export's minimum and maximum pairs are refused as such",
          "[core][signal]") {
  // Rohde & Schwarz RTM scopes in peak-detect mode write a minimum and a maximum at each time
  // stamp: refused as "off the sampling clock of the rounded stamps ... a gap or jump", the
  // cause (and with coarser stamps the clock) not the file's. A column truncated to twice the
  // interval repeats its stamps in pairs as well, its samples in no order: read, rebuilt.
  std::string pairs = "in s,C1 in V\n", truncated = "t_s,x\n";
  char line[64];
  for (int i = 0; i < 200; ++i) {
    const double level = std::sin(0.05 * i), spread = 0.01 * (1 + i % 3);
    std::snprintf(line, sizeof line, "%.6e,%.6f\n%.6e,%.6f\n", 2e-7 * i, level - spread, 2e-7 * i,
                  level + spread);
    pairs += line;
    std::snprintf(line, sizeof line, "%.1e,%.6f\n", 2e-7 * (i / 2), i % 2 ? level : -level);
    truncated += line;
  }
  const auto p = write_file("pairs.csv", pairs);
  CHECK(error_of([&] { read_signal_columns(csv_request(p, {by_index(1)})); })
            .find("pairs.csv: line 3 (time column): 0 s: the time of line 2 again, as every row's "
                  "is its neighbour's, each pair's first values at most its second's: a minimum "
                  "and a maximum per interval") != std::string::npos);
  const auto q = write_file("truncated.csv", truncated);
  const SignalColumns s = read_signal_columns(csv_request(q, {by_index(1)}));
  CHECK(s.dt_s == Approx(1e-7));
  CHECK(s.warnings.front().find("the column was rounded") != std::string::npos);
}

TEST_CASE("Rounded stamps with samples missing are refused, not spread over the record",
          "[core][signal]") {
  // The epoxy file's 3-digit stamps of an 80 ns clock, through zero (where they are finest),
  // with 20 samples missing (a DAQ's dropped buffer) or one row twice with other values: the
  // rebuilt clock spread the gap over the record (every time 0.1 % off, its loading 1.6 us
  // short), exit 0. Read whole (and in µs to one decimal, "%.1f") the base is rebuilt.
  const auto rows = [](int skip_from, int skipped, int twice, const char* format, double unit) {
    std::string text = "t,a\n";
    for (int i = 0; i < 4000; ++i) {
      if (i >= skip_from && i < skip_from + skipped) continue;
      char line[64];
      std::snprintf(line, sizeof line, format, (-1.6e-4 + i * 8e-8) / unit, i);
      text += line;
      if (i == twice) text += std::string(line).substr(0, std::string(line).find(',')) + ",-1\n";
    }
    return text;
  };
  const auto read = [&](const std::string& name, const std::string& text, double unit) {
    SignalRequest r = csv_request(write_file(name, text), {by_index(1)});
    r.time_unit_s = unit;
    return read_signal_columns(r);
  };
  const auto whole = read("whole.csv", rows(0, 0, -1, "%.2E,%d\n", 1), 1);
  CHECK(whole.dt_s == Approx(8e-8).epsilon(1e-12));
  CHECK_NOTHROW(read("whole_us.csv", rows(0, 0, -1, "%.1f,%d\n", 1e-6), 1e-6));
  const std::string gap = error_of([&] { read("gap.csv", rows(3000, 20, -1, "%.2E,%d\n", 1), 1); });
  CHECK(gap.find("gap.csv: line ") != std::string::npos);
  CHECK(gap.find("off the sampling clock of the rounded stamps") != std::string::npos);
  const std::string twice =
      error_of([&] { read("twice.csv", rows(0, 0, 2500, "%.2E,%d\n", 1), 1); });
  CHECK(twice.find("twice.csv: line ") != std::string::npos);
  CHECK(twice.find("samples missing or repeated") != std::string::npos);
}

TEST_CASE("A refusal of default time stamps asks for a time base only where there may be none",
          "[core][signal]") {
  // With no time column named, the first column is read as the time. Its stamps refused, the
  // hint that a file without a time column needs measurement.time.interval fits a first column
  // that is a channel (read as one, or named as no time column is); it was also given for a
  // record whose first column is its time, named so, with a gap in it.
  const std::string hint = "a file without a time column needs its time base";
  struct Case {
    const char* file;
    std::string text;
    std::vector<ColumnRef> columns;
    bool hinted;
  };
  const std::string gap = "0,1,2\n1,1,2\n2,1,2\n5,1,2\n6,1,2\n";  // stamps 0 1 2 5 6
  const std::string back = "0.5,1,2\n0.2,1,2\n0.7,1,2\n";         // a signal's values
  const Case cases[] = {
      {"time_s_gap.csv", "time_s,a,b\n" + gap, {by_name("a")}, false},
      {"time_us_gap.csv", "Time (us),a,b\n" + gap, {by_name("a")}, false},
      {"time_gap.csv", "Time,a,b\n" + gap, {by_name("a")}, false},
      {"t_back.csv", "t,a,b\n" + back, {by_name("a")}, false},
      {"channels_back.csv", "a,b,c\n" + back, {by_name("a"), by_name("b")}, true},
      {"trigger_back.csv", "trigger,a,b\n" + back, {by_name("a")}, true},
      {"time_read_as_channel.csv", "time,a,b\n" + back, {by_index(0), by_name("a")}, true},
      {"no_header_back.csv", back, {by_index(1)}, true},
  };
  for (const Case& c : cases) {
    const std::string e =
        error_of([&] { read_signal_columns(csv_request(write_file(c.file, c.text), c.columns)); });
    INFO(e);
    CHECK(e.find(std::string(c.file) + ": line ") != std::string::npos);
    CHECK((e.find(hint) != std::string::npos) == c.hinted);
  }
}

// A 3 MHz record exported with its time in µs to one decimal: the steps read 0.3, 0.3, 0.4 µs
// (20 % apart, beyond what resampling takes for export jitter), yet every stamp lies within
// 0.05 µs of the uniform clock it was printed from. The base is rebuilt on the least-squares line
// (stamps off it by at most half the 0.1 µs quantum); with one sample missing (a real gap) the
// stamps lie a whole interval off any line and the record is still refused.
TEST_CASE("Stamps printed with too few digits for the sample rate are read on their uniform clock",
          "[core][signal]") {
  constexpr double kInterval = 1e-6 / 3;  // 3 MHz
  constexpr double kQuantum = 1e-7;       // one decimal in µs
  auto text = [&](std::size_t skipped) {
    std::string out = "t_us,a\n";
    for (std::size_t i = 0; i < 3000; ++i) {
      if (i == skipped) continue;
      char line[64];
      std::snprintf(line, sizeof line, "%.1f,%zu\n",
                    -100 + static_cast<double>(i) * 1e6 * kInterval, i);
      out += line;
    }
    return out;
  };
  auto request = csv_request(write_file("rounded_3mhz.csv", text(3000)), {by_index(1)});
  request.time_unit_s = 1e-6;
  const auto s = read_signal_columns(request);
  REQUIRE(s.warnings.size() == 1);
  CHECK(s.warnings[0].find("the column was rounded") != std::string::npos);
  // The least-squares interval of 3000 stamps each within q/2: to 10^-6 of itself.
  CHECK(s.dt_s == Approx(kInterval).epsilon(1e-6));
  for (std::size_t i = 0; i < s.time_s.size(); i += 499)
    CHECK(std::abs(s.time_s[i] - (-100e-6 + static_cast<double>(i) * kInterval)) <= kQuantum / 2);
  auto gap = csv_request(write_file("gap_3mhz.csv", text(1500)), {by_index(1)});
  gap.time_unit_s = 1e-6;
  CHECK(error_of([&] { read_signal_columns(gap); }).find("gap or jump") != std::string::npos);
}

TEST_CASE("Stamps too large for a double to hold to their steps are refused by that cause",
          "[core][signal]") {
  // LabVIEW's absolute time, seconds since 1904: a 1 MS/s record at 3786825658.312841 s written
  // exactly to the microsecond. A double holds that to 2^-21 s = 0.477 us, so the steps read 0.95
  // and 1.43 us: once refused as "a gap or jump in the record", which it has none of. The same
  // stamps 100 s into the acquisition are read on their 1 us clock.
  auto text = [](long long seconds) {
    std::string out = "time_s,a\n";
    for (int i = 0; i < 600; ++i) {
      char line[64];
      std::snprintf(line, sizeof line, "%lld.%06d,%d\n", seconds, 312841 + i, i);
      out += line;
    }
    return out;
  };
  const std::string refused = error_of([&] {
    read_signal_columns(csv_request(write_file("epoch.csv", text(3786825658LL)), {by_index(1)}));
  });
  CHECK(refused.find("epoch.csv: line 601 (time column)") != std::string::npos);
  CHECK(refused.find("time stamps this large are read to 4.76837e-07 s") != std::string::npos);
  CHECK(refused.find("gap or jump") == std::string::npos);
  const auto read =
      read_signal_columns(csv_request(write_file("armed.csv", text(100)), {by_index(1)}));
  CHECK(read.dt_s == Approx(1e-6).epsilon(1e-9));
  CHECK(read.warnings.empty());
}

// A scope export at 10 MHz written in a fixed format: row i holds t = i·0.1 µs and the value i.
std::vector<std::string> fixed_format_rows(int n) {
  std::vector<std::string> rows;
  for (int i = 0; i < n; ++i) {
    char line[64];
    std::snprintf(line, sizeof line, "%.6e,%.6e", i * 1e-7, -1e-6 * i);
    rows.emplace_back(line);
  }
  return rows;
}
std::string lines_of(const std::vector<std::string>& rows, bool final_newline = true) {
  std::string text = "time_s,incident\n";
  for (const auto& r : rows) text += r + "\n";
  if (!final_newline) text.pop_back();
  return text;
}

TEST_CASE(
    "A row exported twice is skipped by its line; a repeated time with other values is "
    "refused",
    "[core][signal]") {
  auto rows = fixed_format_rows(1000);
  rows.insert(rows.begin() + 501, rows[500]);  // row 500 (line 502) again, on line 503
  const auto s =
      read_signal_columns(csv_request(write_file("twice.csv", lines_of(rows)), {by_index(1)}));
  REQUIRE(s.warnings.size() == 1);
  CHECK(s.warnings[0].find("twice.csv: line 503 repeats the row before") != std::string::npos);
  // Every sample keeps its own time and value: nothing shifted by the repeat.
  REQUIRE(s.time_s.size() == 1000);
  constexpr double kStampDigits = 1e-6;  // %.6e: 7 significant digits
  for (int i : {0, 500, 501, 999}) {
    CHECK(s.time_s[static_cast<std::size_t>(i)] == Approx(i * 1e-7).epsilon(kStampDigits));
    CHECK(s.values[0][static_cast<std::size_t>(i)] == Approx(-1e-6 * i).epsilon(kStampDigits));
  }
  CHECK(s.dt_s == Approx(1e-7).epsilon(kStampDigits));

  // Rows exported twice however many: every 20th (5 %, beyond the 2 % a rounding step may
  // repeat) is still skipped, not taken for a rounded column whose base is rebuilt at 10.5 MHz.
  auto often = fixed_format_rows(1000);
  for (int i = 990; i >= 10; i -= 20)
    often.insert(often.begin() + i, often[static_cast<std::size_t>(i)]);
  const auto o =
      read_signal_columns(csv_request(write_file("often.csv", lines_of(often)), {by_index(1)}));
  REQUIRE(o.warnings.size() == 1);
  CHECK(o.warnings[0].find("often.csv: lines 13, 34, ") != std::string::npos);
  CHECK(o.warnings[0].find(" and 40 more repeat the row before") != std::string::npos);
  CHECK(o.time_s.size() == 1000);
  CHECK(o.dt_s == Approx(1e-7).epsilon(kStampDigits));

  rows[501] = rows[500].substr(0, rows[500].find(',')) + ",1.000000e-03";
  const auto msg = error_of([&] {
    read_signal_columns(csv_request(write_file("clash.csv", lines_of(rows)), {by_index(1)}));
  });
  CHECK(msg.find("clash.csv: line 503 (time column): 5e-05 s") != std::string::npos);
  CHECK(msg.find("strictly increasing time") != std::string::npos);
}

TEST_CASE("A last line cut inside a number that still parses is refused where the format shows it",
          "[core][signal]") {
  auto rows = fixed_format_rows(100);
  rows.back() = rows.back().substr(0, rows.back().find(',') + 5);  // "…,-9.9" of "-9.900000e-05"
  const auto msg = error_of([&] {
    read_signal_columns(
        csv_request(write_file("cut.csv", lines_of(rows, false)), {by_name("incident")}));
  });
  CHECK(msg.find("cut.csv: line 101, column 2 (\"incident\"): \"-9.9\"") != std::string::npos);
  CHECK(msg.find("cut off") != std::string::npos);
  // Nothing to judge by: the same line ending a file with a line end (written so), or a column
  // of varying widths, or a complete last line without a line end, is read.
  CHECK_NOTHROW(read_signal_columns(
      csv_request(write_file("short.csv", lines_of(rows)), {by_name("incident")})));
  CHECK_NOTHROW(read_signal_columns(csv_request(
      write_file("g.csv", "time_s,incident\n0,0\n1e-07,-1e-06\n2e-07,-2.5e-06\n3e-07,-1.2"),
      {by_name("incident")})));
  CHECK_NOTHROW(read_signal_columns(csv_request(
      write_file("whole.csv", lines_of(fixed_format_rows(100), false)), {by_name("incident")})));
}

TEST_CASE("A data row with more fields than the first is refused: its columns are shifted",
          "[core][signal]") {
  // "1,5" in a comma-separated file without a header, or in a Tektronix channel file, splits a
  // sample in two: the columns after it would be read from their neighbours ("1" as the sample).
  const auto plain = write_file("split.csv", "0,0,0\n1e-07,-1e-06,0\n2e-07,1,5,0\n3e-07,0,0\n");
  CHECK(error_of([&] {
          read_signal_columns(csv_request(plain, {by_index(1)}));
        }).find("split.csv: line 3: 4 fields: expected at most the 3 of line 1") !=
        std::string::npos);
  const auto tek = write_file("tek_split.csv",
                              "\"Record Length\",4,\"Points\",-8.0e-005,-0.5\r\n"
                              "\"Sample Interval\",8.0e-009,s,-7.9992e-005,-0.25\r\n"
                              ",,,-7.9984e-005,0,25\r\n,,,-7.9976e-005,0.25\r\n");
  CHECK(error_of([&] {
          read_signal_columns(csv_request(tek, {by_index(4)}));
        }).find("tek_split.csv: line 3: 6 fields: expected at most the 5 of line 1") !=
        std::string::npos);
  // Trailing separators add no field; a text beside the numbers (a scope's marker) shifts none,
  // and a workbook's cells are cells.
  CHECK_NOTHROW(read_signal_columns(csv_request(
      write_file("trail.csv", "0,0,0\n1e-07,-1e-06,0,\n2e-07,0,0,,\n"), {by_index(1)})));
  CHECK_NOTHROW(read_signal_columns(csv_request(
      write_file("marker.csv", "0,0,0\n1e-07,-1e-06,0,TRIGGER\n2e-07,0,0\n"), {by_index(1)})));
  const auto sheet = scratch.path() / "note.xlsx";
  shpb_test::write_xlsx(sheet, "t,a,b\n0,0,0\n1e-07,-1e-06,0,7\n2e-07,0,0\n");
  SignalRequest from_sheet = csv_request(sheet, {by_index(1)});
  from_sheet.sheet = "signals";
  CHECK_NOTHROW(read_signal_columns(from_sheet));
}

TEST_CASE("A last line cut inside the exponent of a fixed-format column is refused",
          "[core][signal]") {
  // Tektronix writes "-1.16812501e-001"; cut to "-1.16812501e-0" it still parses, ten times the
  // sample.
  std::string text =
      "\"Record Length\",4,\"Points\",-8.00000000e-005,-1.15562501e-001\r\n"
      "\"Sample Interval\",8.00000000e-009,s,-7.99920000e-005,-1.15875001e-001\r\n"
      ",,,-7.99840000e-005,-1.18437501e-001\r\n,,,-7.99760000e-005,-1.16812501e-0";
  const std::string msg = error_of(
      [&] { read_signal_columns(csv_request(write_file("tek_cut.csv", text), {by_index(4)})); });
  CHECK(msg.find("tek_cut.csv: line 4, column 5: \"-1.16812501e-0\"") != std::string::npos);
  CHECK(msg.find("an exponent of 1 digit where every other value of the column has 8 decimals and "
                 "an exponent of 3 digits") != std::string::npos);
}

TEST_CASE("A value of megabytes is quoted in a message by its start and its length",
          "[core][signal]") {
  const std::string junk(1 << 20, 'x');
  const auto p = write_file("long.csv", "time_s,incident\n0,0\n1e-07," + junk + "\n2e-07,0\n");
  const std::string msg =
      error_of([&] { read_signal_columns(csv_request(p, {by_name("incident")})); });
  CHECK(msg.find("long.csv: line 3, column 2 (\"incident\"): \"xxx") != std::string::npos);
  CHECK(msg.find("... (1048578 bytes)") != std::string::npos);
  constexpr std::size_t kShortMessage = 1000;  // a line a terminal shows, whatever the field
  CHECK(msg.size() < kShortMessage);
}

TEST_CASE("A header naming many more columns than the rows hold is read", "[core][signal]") {
  // Its fields are counted by the file's bytes, not by the header's names times the rows: a
  // million names over 20 000 rows reserved 320 GB (exit 3, out of memory).
  std::string text = "time_s,incident";
  for (int i = 0; i < 1000000; ++i) text += ",c";
  text += "\n";
  for (int i = 0; i < 20000; ++i) text += std::to_string(i) + "e-07,0\n";
  const auto s =
      read_signal_columns(csv_request(write_file("wide_header.csv", text), {by_name("incident")}));
  CHECK(s.values[0].size() == 20000);
}

TEST_CASE("Tektronix and LANL raw files are read with their own time bases", "[core][signal]") {
  SECTION("Tektronix") {
    const auto p = write_file("tek.csv",
                              "\"Record Length\",4,\"Points\",-8.0e-005,-0.5\r\n"
                              "\"Sample Interval\",8.0e-009,s,-7.9992e-005,-0.25\r\n"
                              ",,,-7.9984e-005,0.0\r\n,,,-7.9976e-005,0.25\r\n");
    SignalRequest r;
    r.file = p;
    r.columns = {by_index(4)};
    const auto s = read_signal_columns(r);
    CHECK(s.format == SignalFormat::kTektronix);
    CHECK(s.values[0] == std::vector<double>{-0.5, -0.25, 0, 0.25});
    CHECK(s.dt_s == Approx(8e-9));
  }
  SECTION("LANL raw") {
    const auto p = write_file("x.raw",
                              "Test Date\t12/1/2006\tIncident\tTransmitted\r\n"
                              "Sample Length(mm)\t3.2\t-5.00E-05\t-5.00E-05\r\n"
                              "Test Temperature(\xb0"
                              "C)\t0\t1.00E-07\t1.00E-07\r\n"
                              "\t\t0.5\t-0.5\r\n\t\t1.5\t-1.5\r\n\t\t2.5\t-2.5\r\n");
    SignalRequest r;
    r.file = p;
    r.columns = {by_name("Transmitted")};
    const auto s = read_signal_columns(r);
    CHECK(s.format == SignalFormat::kLanlRaw);
    CHECK(s.values[0] == std::vector<double>{-0.5, -1.5, -2.5});
    CHECK(s.time_s[2] == Approx(-5e-5 + 2e-7));
    CHECK(s.dt_s == 1e-7);
  }
}

TEST_CASE("A LANL header's sample interval is quoted as written, not as %f would print it",
          "[core][signal][format]") {
  // (interval, start) as the header gives them, and what the message must quote: %f printed
  // -1e-07 as "-0.000000" and 1e308 as a 309-digit number.
  for (const auto& [interval, start, quoted] :
       {std::tuple{"-1.00E-07", "-5.00E-05", "-1e-07 s"},
        std::tuple{"1.00E-07", "1.00E+308", "start time 1e+308 s"}}) {
    CAPTURE(interval, start);
    const auto p = write_file("x.raw", std::string("Test Date\t12/1/2006\tIncident\r\n") +
                                           "Sample Length(mm)\t3.2\t" + start + "\r\n" +
                                           "Test Temperature(C)\t0\t" + interval + "\r\n" +
                                           "\t\t0.5\r\n\t\t1.5\r\n\t\t2.5\r\n");
    SignalRequest r;
    r.file = p;
    r.columns = {by_name("Incident")};
    try {
      read_signal_columns(r);
      FAIL("accepted");
    } catch (const InputError& e) {
      const std::string m = e.what();
      INFO(m);
      CHECK(m.find(quoted) != std::string::npos);
      CHECK(m.find("0.000000") == std::string::npos);
      constexpr std::size_t kOneLine = 200;  // a message, not a page of digits
      CHECK(m.size() < kOneLine);
    }
  }
}

TEST_CASE("Volts become strain through the bridge and opposite gauges are averaged",
          "[core][signal]") {
  // Half bridge, GF 2, gain 100, 10 V: ε = 2 V / 2000.
  CHECK(volts_to_strain({2, 2.0, 10.0, 100.0}) == Approx(1e-3));
  const auto a = write_file("ga.csv", "t,v\n0,0\n1,-1\n2,-2\n3,0\n");
  const auto b = write_file("gb.csv", "t,v\n0,0\n1,-3\n2,-2\n3,0\n");
  MeasurementSpec m;
  m.time_unit_s = 1e-6;  // a 1 MHz record (a 1 s interval is refused as no digitizer's)
  for (const auto& f : {a, b}) {
    ChannelSpec c;
    c.gauge = "incident";
    c.file = f;
    c.column = by_name("v");
    c.unit = SignalUnit::kVolt;
    c.bridge = BridgeSpec{2, 2.0, 10.0, 100.0};
    c.invert = true;
    m.channels.push_back(c);
  }
  const GaugeSignals g = read_gauge_signals(m, {});
  REQUIRE(g.find("incident"));
  CHECK((*g.find("incident"))[1] == Approx(2e-3));  // mean of 1 and 3 V, inverted
  CHECK(g.warnings.empty());                        // peak 2e-3 is a plausible strain
}

namespace {
// A pulse of strain -1e-3 over samples [30, 70) of 100 at 10 MHz, with `bending` of the other
// sign on the channel's opposite gauge, times `scale` (a channel's own gain).
std::string pulse_csv(double bending, double scale) {
  std::ostringstream s;
  s.precision(17);
  s << "t,v\n";
  for (int i = 0; i < 100; ++i)
    s << i * 1e-7 << "," << (i >= 30 && i < 70 ? -1e-3 * (1 + bending) * scale : 0.0) << "\n";
  return s.str();
}

// One gauge read from two files, each a channel in strain.
MeasurementSpec twin_channels(const fs::path& a, const fs::path& b) {
  MeasurementSpec m;
  for (const auto& f : {a, b}) {
    ChannelSpec c;
    c.gauge = "incident";
    c.file = f;
    c.column = by_index(1);
    c.unit = SignalUnit::kStrain;
    m.channels.push_back(c);
  }
  return m;
}
}  // namespace

TEST_CASE("Two channels of one gauge that disagree are refused, never averaged", "[core][signal]") {
  // Opposite gauges of one section read the axial strain plus and minus the bending strain: with
  // 10 % bending (a fairly misaligned bar) the mean is the axial strain.
  const auto good = write_file("ch1.csv", pulse_csv(0.1, 1));
  const auto other = write_file("ch2.csv", pulse_csv(-0.1, 1));
  const GaugeSignals g = read_gauge_signals(twin_channels(good, other), {});
  CHECK((*g.find("incident"))[50] == Approx(-1e-3));
  // A dead channel (zeros), one whose gain is a million times off and one wired the other way
  // would halve, or cancel, the gauge's strain: each is refused naming its file and channel.
  for (const auto& [name, text] :
       {std::pair{"dead.csv", pulse_csv(0, 0)}, std::pair{"micro.csv", pulse_csv(0, 1e-6)},
        std::pair{"inverted.csv", pulse_csv(0, -1)}}) {
    const auto bad = write_file(name, text);
    const std::string msg = error_of([&] { read_gauge_signals(twin_channels(good, bad), {}); });
    INFO(msg);
    CHECK(msg.find("ch1.csv: column index 1 (measurement.channels[0], gauge \"incident\"): with " +
                   bad.string() +
                   ", column index 1 (measurement.channels[1], gauge \"incident\"): "
                   "each ") != std::string::npos);
    CHECK(msg.find("expected the channels of one gauge") != std::string::npos);
  }
}

TEST_CASE("A sample no unit slip explains is refused by its line and column", "[core][signal]") {
  // Beyond 5e4, what a plausible strain (5e-2) in microstrain declared as strain reads: carried
  // into the reduction (a column scaled by 1e300) it overflowed to inf in summary.json.
  std::string text = "t,v\n";
  for (int i = 0; i < 100; ++i)
    text += std::to_string(i) + "e-07," + (i == 50 ? "-2.5e+293" : "0") + "\n";
  MeasurementSpec m = twin_channels(write_file("huge.csv", text), {});
  m.channels.resize(1);
  const std::string msg = error_of([&] { read_gauge_signals(m, {}); });
  CHECK(msg.find(
            "huge.csv: line 52, column index 1 (measurement.channels[0], gauge "
            "\"incident\"): -2.5e+293 read as strain -2.5e+293: expected |strain| within 50000") !=
        std::string::npos);
}

TEST_CASE("A channel file that records next to nothing of the first file's time is refused",
          "[core][signal]") {
  // Two scopes' files of one test: the second written in ms where the first is in s. Read in s it
  // spans 1000 times the time, with a sample or two inside the first's record, and resampled onto
  // the first's clock it would be a flat line.
  // 10 MHz records; the second file's 1e-4 ms interval, read as s, is a digitizer's 10 kHz.
  std::string first = "t,v\n", other = "t,v\n", later = "t,v\n";
  const auto row = [](double t) {
    std::ostringstream s;
    s << t << ",1\n";
    return s.str();
  };
  for (int i = 0; i < 100; ++i) {
    first += row(i * 1e-7);
    other += row(i * 1e-4);
    later += row((i + 50) * 1e-7);  // the same clock, from sample 50 on
  }
  MeasurementSpec m;
  for (const auto& [gauge, text] :
       {std::pair{"incident", first}, std::pair{"transmitted", other}}) {
    ChannelSpec c;
    c.gauge = gauge;
    c.file = write_file(std::string(gauge) + ".csv", text);
    c.column = by_index(1);
    c.unit = SignalUnit::kStrain;
    m.channels.push_back(c);
  }
  const std::string error = error_of([&] { read_gauge_signals(m, {}); });
  INFO(error);
  CHECK(error.find("transmitted.csv: time column: 1 samples") != std::string::npos);
  CHECK(error.find("is the time unit the same in both files") != std::string::npos);
  // A file that starts later on the same clock is resampled, with a warning.
  m.channels[1].file = write_file("later.csv", later);
  const GaugeSignals g = read_gauge_signals(m, {});
  REQUIRE(g.warnings.size() >= 1);
  CHECK(g.warnings[0].find("later.csv: time base differs") != std::string::npos);
}

TEST_CASE("A value column's unit in the header must be the unit its channel reads",
          "[core][signal]") {
  // Scopes name a column's unit in its header ("CH1 (mV)", PicoScope's unit row "(mV)",
  // Keysight's "Volt", catman's "µm/m"): read in another unit the strain is 1000 or 10^6 times
  // off, which only a plausibility warning would hint at. A name without a unit says nothing.
  struct Case {
    std::string head;
    SignalUnit unit;
    std::string refused;  // the hint of the refusal ("": read)
  };
  const Case cases[] = {
      {"t,v (mV)", SignalUnit::kVolt, "set \"unit\": \"mV\""},
      {"t,v (mV)", SignalUnit::kMillivolt, ""},
      {"Time,Channel A\n(us),(mV)", SignalUnit::kVolt, "set \"unit\": \"mV\""},
      {"x-axis,1\nus,Volt", SignalUnit::kMillivolt, "set \"unit\": \"V\""},
      {"x-axis,1\nus,Volt", SignalUnit::kVolt, ""},
      {"t,inc [\xc2\xb5\xce\xb5]", SignalUnit::kStrain, "set \"unit\": \"microstrain\""},
      {"t,inc [\xb5\xce\xb5]", SignalUnit::kMicrostrain, ""},
      {"Zeit,DMS\nus,\xb5m/m", SignalUnit::kStrain, "set \"unit\": \"microstrain\""},
      {"t,v (V)", SignalUnit::kMicrostrain, "set \"unit\": \"V\""},
      {"t,v (kV)", SignalUnit::kVolt, "convert the column to V, mV, strain or microstrain"},
      {"t,Dehnung [%]", SignalUnit::kStrain, "convert the column to V, mV, strain or microstrain"},
      {"t,v_A", SignalUnit::kVolt, ""},
      {"t,inc_mV", SignalUnit::kStrain, ""},  // a name (a simulated gauge's), not a unit
      {"t,incident_bar_signal/voltage", SignalUnit::kVolt, ""},
      {"t,strain", SignalUnit::kVolt, ""},
  };
  // Strain per volt of the volt channels: 2e-3 at a 0.5 V or 500 mV plateau gives 1e-3.
  constexpr double kScale = 2e-3;
  for (const auto& c : cases) {
    DYNAMIC_SECTION(c.head << " read in " << enum_name(kSignalUnitNames, c.unit)) {
      const auto p = write_file("value_unit.csv", c.head + "\n0,0\n1,500\n2,500\n3,0\n");
      MeasurementSpec m;
      m.time_unit_s = 1e-6;  // a 1 MHz record
      ChannelSpec ch;
      ch.gauge = "incident";
      ch.file = p;
      ch.column = by_index(1);
      ch.unit = c.unit;
      if (c.unit == SignalUnit::kVolt || c.unit == SignalUnit::kMillivolt) ch.scale = kScale;
      m.channels.push_back(ch);
      const std::string error = error_of([&] { read_gauge_signals(m, {}); });
      INFO(error);
      if (c.refused.empty()) {
        CHECK(error.empty());
      } else {
        CHECK(error.find("value_unit.csv: line ") != std::string::npos);
        CHECK(error.find("the header gives the values in") != std::string::npos);
        CHECK(error.find(c.refused) != std::string::npos);
      }
    }
  }
  SECTION("a column in mV is read as thousandths of a volt") {
    const auto p = write_file("millivolt.csv", "t,v (mV)\n0,0\n1,500\n2,500\n3,0\n");
    MeasurementSpec m;
    m.time_unit_s = 1e-6;
    ChannelSpec ch;
    ch.gauge = "incident";
    ch.file = p;
    ch.column = by_index(1);
    ch.unit = SignalUnit::kMillivolt;
    ch.scale = kScale;
    m.channels.push_back(ch);
    const GaugeSignals g = read_gauge_signals(m, {});
    REQUIRE(g.find("incident"));
    CHECK((*g.find("incident"))[1] == Approx(0.5 * kScale));  // 500 mV = 0.5 V
  }
}

TEST_CASE("The real files import: LANL raw, Tektronix channels, and the messy epoxy file",
          "[core][signal]") {
  SECTION("LANL copper raw") {
    SignalRequest r;
    r.file = kExperiments / "lanl-cu-ofe-273k/data/20061201_1148HE_CuOFE_273K.raw";
    r.columns = {by_name("Incident/Reflected Waveform"), by_name("Transmitted Waveform")};
    const auto s = read_signal_columns(r);
    CHECK(s.time_s.size() == 5000);
    CHECK(s.dt_s == 1e-7);
    CHECK(s.time_s.front() == -5e-5);
  }
  SECTION("PMMA Tektronix") {
    SignalRequest r;
    r.file = kExperiments / "lanl-pmma13-mini-kolsky/data/180303_171828_Ch1.csv";
    r.columns = {by_index(4)};
    const auto s = read_signal_columns(r);
    CHECK(s.time_s.size() == 50000);
    CHECK(s.dt_s == Approx(8e-9).epsilon(1e-6));
  }
  SECTION("epoxy: rebuilt clock and doubtful scale") {
    MeasurementSpec m;
    m.file = kExperiments / "epoxy-resin-sample01/data/raw_strain.csv";
    m.time_column = by_name("Time/s");
    for (int i : {1, 2}) {
      ChannelSpec c;
      c.gauge = i == 1 ? "incident" : "transmitted";
      c.column = by_index(i);
      m.channels.push_back(c);
    }
    const GaugeSignals g = read_gauge_signals(m, {});
    REQUIRE(g.warnings.size() == 3);
    CHECK(g.warnings[0].find("time stamps repeat") != std::string::npos);
    CHECK(g.dt_s == Approx(8e-8).epsilon(1e-12));
    CHECK(g.warnings[1].find("implausible strain scale") != std::string::npos);
    CHECK(g.warnings[2].find("implausible strain scale") != std::string::npos);
  }
}

}  // namespace tests_core_test_signal_reader
