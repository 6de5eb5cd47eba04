// Excel workbooks are untrusted input (docs/scene-format.md (measurement)): a zip bomb, a flood of
// shared strings or a corrupted .xls is one error line and exit 2, never gigabytes of memory, a
// crash or a read that ignores SIGINT/SIGTERM. Every case runs the real executable.
#include <signal.h>
#include <zlib.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <chrono>
#include <cstdint>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "../app/write_xlsx.hpp"
#include "child_process.hpp"

// This file's own names: the test files are compiled in batches (CMakeLists.txt, unity build).
namespace tests_robustness_test_spreadsheets {

namespace {

using namespace shpb_robust;

const fs::path kClassic = fs::path(SHPB_SOURCE_DIR) / "experiments/classic-al6061/scene.json";
constexpr double kLimit_s = 120.0;  // a hang, not a slow machine

// One part of a hand-made zip: its name, the bytes stored, the method (0 stored, 8 deflated),
// the CRC-32 and the uncompressed size the directory declares.
struct ZipEntry {
  std::string name, data;
  int method = 0;
  std::uint32_t crc = 0;
  std::uint64_t size = 0;
};

ZipEntry stored(const std::string& name, const std::string& text) {
  return {name, text, 0,
          static_cast<std::uint32_t>(crc32(0, reinterpret_cast<const Bytef*>(text.data()),
                                           static_cast<uInt>(text.size()))),
          text.size()};
}

// A deflated part of `prefix`, `block` × `repeats`, `suffix` whose deflate stream is built without
// compressing the repeats: `block` is deflated once after a full flush (no back-reference crosses
// it) and those bytes are repeated. 1 MiB of one short element deflates to about 1 kB: a part of
// gigabytes from a file of megabytes, as a zip bomb is made.
ZipEntry deflated_repeats(const std::string& name, const std::string& prefix,
                          const std::string& block, std::uint64_t repeats,
                          const std::string& suffix) {
  z_stream z{};
  REQUIRE(deflateInit2(&z, 9, Z_DEFLATED, -15, 9, Z_DEFAULT_STRATEGY) == Z_OK);
  const auto run = [&](const std::string& in, int flush) {
    std::string out;
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in.data()));
    z.avail_in = static_cast<uInt>(in.size());
    std::vector<char> buffer(1 << 16);
    do {
      z.next_out = reinterpret_cast<Bytef*>(buffer.data());
      z.avail_out = static_cast<uInt>(buffer.size());
      deflate(&z, flush);
      out.append(buffer.data(), buffer.size() - z.avail_out);
    } while (z.avail_out == 0);
    return out;
  };
  const std::string head = run(prefix, Z_FULL_FLUSH), body = run(block, Z_FULL_FLUSH),
                    tail = run(suffix, Z_FINISH);
  deflateEnd(&z);
  ZipEntry e{name, head, 8, 0, prefix.size() + block.size() * repeats + suffix.size()};
  e.data.reserve(head.size() + body.size() * repeats + tail.size());
  for (std::uint64_t k = 0; k < repeats; ++k) e.data += body;
  e.data += tail;
  const auto crc_of = [](const std::string& s) {
    return crc32(0, reinterpret_cast<const Bytef*>(s.data()), static_cast<uInt>(s.size()));
  };
  uLong crc = crc_of(prefix);
  const uLong block_crc = crc_of(block);
  for (std::uint64_t k = 0; k < repeats; ++k)
    crc = crc32_combine(crc, block_crc, static_cast<z_off_t>(block.size()));
  e.crc = static_cast<std::uint32_t>(
      crc32_combine(crc, crc_of(suffix), static_cast<z_off_t>(suffix.size())));
  return e;
}

void put(std::string& s, std::uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) s.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}

// A zip archive (PKWARE APPNOTE 4.3: local headers, central directory, end record; sizes below
// 4 GiB) whose directory declares each entry's `size`, whatever its data inflate to.
void write_zip_entries(const fs::path& file, const std::vector<ZipEntry>& entries) {
  std::string zip, directory;
  for (const auto& e : entries) {
    const std::uint64_t offset = zip.size();
    for (std::string* h : {&zip, &directory}) {
      const bool central = h == &directory;
      put(*h, central ? 0x02014b50 : 0x04034b50, 4);
      if (central) put(*h, 20, 2);  // made by
      put(*h, 20, 2);               // needed
      put(*h, 0, 2);                // flags
      put(*h, static_cast<std::uint64_t>(e.method), 2);
      put(*h, 0, 4);  // time, date
      put(*h, e.crc, 4);
      put(*h, e.data.size(), 4);
      put(*h, e.size, 4);
      put(*h, e.name.size(), 2);
      put(*h, 0, 2);  // extra
      if (central) {
        put(*h, 0, 2);  // comment
        put(*h, 0, 2);  // disk
        put(*h, 0, 2);  // internal attributes
        put(*h, 0, 4);  // external attributes
        put(*h, offset, 4);
      }
      *h += e.name;
    }
    zip += e.data;
  }
  const std::uint64_t directory_offset = zip.size();
  zip += directory;
  put(zip, 0x06054b50, 4);
  put(zip, 0, 4);  // disks
  put(zip, entries.size(), 2);
  put(zip, entries.size(), 2);
  put(zip, directory.size(), 4);
  put(zip, directory_offset, 4);
  put(zip, 0, 2);
  write_bytes(file, zip);
}

// The small parts of a one-sheet workbook ("signals", xl/worksheets/sheet1.xml).
std::vector<ZipEntry> workbook_parts() {
  return {stored("xl/workbook.xml",
                 "<workbook><sheets><sheet name=\"signals\" sheetId=\"1\" r:id=\"rId1\" "
                 "xmlns:r=\"r\"/></sheets></workbook>"),
          stored("xl/_rels/workbook.xml.rels",
                 "<Relationships><Relationship Id=\"rId1\" "
                 "Target=\"worksheets/sheet1.xml\"/></Relationships>")};
}

const std::string kSheetHead = "<worksheet><sheetData>", kSheetTail = "</sheetData></worksheet>";

// 1 MiB of numeric cells (<c><v>1</v></c>, 15 bytes each; 4 to a row: a period deflate's
// 258-byte matches span several times, about 1000:1).
std::string cells_block() {
  std::string row = "<row>";
  for (int c = 0; c < 4; ++c) row += "<c><v>1</v></c>";
  row += "</row>";
  std::string block;
  while (block.size() + row.size() <= (1u << 20)) block += row;
  return block;
}

std::vector<std::string> process(const fs::path& signals, const fs::path& dir) {
  return {"process", kClassic.string(),      "--signals", signals.string(),
          "-o",      (dir / "out").string(), "-q"};
}

}  // namespace

TEST_CASE("A zip-bomb .xlsx is refused from its zip directory, or as it inflates past it",
          "[robustness][limits][excel]") {
  ScratchFolder scratch("xlsx_bomb");
  // 1000 MiB of cells (some 59 million) in a few megabytes of file.
  const ZipEntry bomb =
      deflated_repeats("xl/worksheets/sheet1.xml", kSheetHead, cells_block(), 1000, kSheetTail);
  REQUIRE(bomb.data.size() < 4u << 20);  // 3.6 MB
  std::vector<ZipEntry> honest = workbook_parts(), lying = workbook_parts();
  honest.push_back(bomb);
  lying.push_back(bomb);
  lying.back().size = 1u << 20;  // the directory claims 1 MiB
  for (const auto& [name, entries, expected] :
       {std::tuple{"honest.xlsx", honest, "bytes uncompressed: beyond the 536870912 bytes"},
        std::tuple{"lying.xlsx", lying, "inflates beyond the 1048576 bytes"}}) {
    CAPTURE(name);
    const fs::path file = scratch.path() / name;
    write_zip_entries(file, entries);
    const Outcome o = run(process(file, scratch.path()), scratch.path(), kLimit_s);
    INFO(o.err);
    CHECK(o.code == 2);
    CHECK(o.seconds < prompt_exit_s());
    CHECK(o.err.find(std::string(name) + ": part xl/worksheets/sheet1.xml") != std::string::npos);
    CHECK(o.err.find(expected) != std::string::npos);
    CHECK_FALSE(fs::exists(scratch.path() / "out"));
  }
}

TEST_CASE(
    "A workbook with more shared strings than a signal sheet has is refused before they "
    "are stored",
    "[robustness][limits][excel]") {
  ScratchFolder scratch("xlsx_strings");
  const std::string sheet = kSheetHead + "<row><c t=\"s\"><v>0</v></c></row>" + kSheetTail;
  // Declared (uniqueCount), and undeclared: 1048577 empty strings, one more than a full sheet's
  // rows.
  const std::string declared = "<sst uniqueCount=\"4000000000\"><si><t>x</t></si></sst>";
  std::vector<ZipEntry> a = workbook_parts();
  a.push_back(stored("xl/worksheets/sheet1.xml", sheet));
  std::vector<ZipEntry> b = a;
  a.push_back(stored("xl/sharedStrings.xml", declared));
  std::string many = "<sst>";
  for (int k = 0; k < 1048577; ++k) many += "<si/>";
  many += "</sst>";
  b.push_back(deflated_repeats("xl/sharedStrings.xml", many, "", 0, ""));
  for (const auto& [name, entries, expected] :
       {std::tuple{"declared.xlsx", a, "4000000000 shared strings: beyond the 1048576"},
        std::tuple{"counted.xlsx", b, "more than 1048576 shared strings: beyond the 1048576"}}) {
    CAPTURE(name);
    const fs::path file = scratch.path() / name;
    write_zip_entries(file, entries);
    const Outcome o = run(process(file, scratch.path()), scratch.path(), kLimit_s);
    INFO(o.err);
    CHECK(o.code == 2);
    CHECK(o.err.find(std::string(name) + ": part xl/sharedStrings.xml: " + expected) !=
          std::string::npos);
  }
}

TEST_CASE("SIGTERM and SIGINT stop the reading of a large .xlsx within a second",
          "[robustness][limits][interrupt][excel]") {
  ScratchFolder scratch("xlsx_interrupt");
  // 480 MiB of empty rows for the optimised build (within the reading limits, no cell stored):
  // inflating and parsing them is the whole run (it then finds an empty sheet, exit 2).
  std::string rows;
  while (rows.size() < (1u << 20) - 6) rows += "<row/>";
  std::vector<ZipEntry> entries = workbook_parts();
  entries.push_back(deflated_repeats("xl/worksheets/sheet1.xml", kSheetHead, rows,
                                     static_cast<std::uint64_t>(same_run_length(480)), kSheetTail));
  const fs::path file = scratch.path() / "large.xlsx";
  write_zip_entries(file, entries);
  const auto args = process(file, scratch.path());
  // The signal lands a tenth and a third of the way through the reading on this machine; a run
  // faster than the one timed (exit 2: the empty sheet) gets the signal twice as early, up to
  // five times.
  const double run_s = seconds_after_startup(args, scratch.path(), kLimit_s);
  REQUIRE(run_s > 0);
  int k = 0;
  for (const double fraction : {0.1, 0.33}) {
    const int sig = k++ ? SIGINT : SIGTERM;
    double delay_s = fraction * run_s;
    const Outcome o = interrupted_run(args, scratch.path(), sig, delay_s, kLimit_s);
    INFO("signal " << sig << " after " << delay_s << " s of a " << run_s << " s run");
    INFO(o.err);
    CHECK(o.signal == 0);
    CHECK(o.code == 130);
    CHECK(o.seconds < prompt_exit_s());
    CHECK_FALSE(fs::exists(scratch.path() / "out"));
  }
}

TEST_CASE("A corrupted .xls that sends the .xls library past its buffers is refused with exit 2",
          "[robustness][limits][excel]") {
  ScratchFolder scratch("xls_corrupt");
  std::string xls = read_all(fs::path(SHPB_SOURCE_DIR) / "tests/data/signals.xls");
  // The OLE2 directory entry of the "Workbook" stream: its name in UTF-16 (64 bytes) and then the
  // name's size in bytes (18). A size of 0xE412 (58 386 bytes) made FreeXL convert that many bytes
  // from its 64-byte name buffer on the stack (AddressSanitizer: stack-buffer-underflow in iconv).
  const std::string name("W\0o\0r\0k\0b\0o\0o\0k\0", 16);
  const auto at = xls.find(name);
  REQUIRE(at != std::string::npos);
  REQUIRE(xls[at + 64] == 18);
  xls[at + 65] = static_cast<char>(0xE4);
  const fs::path file = scratch.path() / "corrupt.xls";
  write_bytes(file, xls);
  const Outcome o = run(process(file, scratch.path()), scratch.path(), kLimit_s);
  INFO(o.err);
  CHECK(o.signal == 0);
  CHECK(o.code == 2);
  CHECK(o.err.find("corrupt.xls") != std::string::npos);
  CHECK(std::count(o.err.begin(), o.err.end(), '\n') == 1);
}

}  // namespace tests_robustness_test_spreadsheets
