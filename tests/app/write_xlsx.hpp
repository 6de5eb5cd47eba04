#pragma once
// Minimal .xlsx workbooks for the tests: sheets "notes" (text) and "signals", zipped with libzip.
#include <zip.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace shpb_test {

using ZipParts = std::vector<std::pair<std::string, std::string>>;  // name, content

// The parts of a workbook whose sheet "signals" holds `rows` (<row> elements) and whose shared
// strings are `shared`.
inline ZipParts xlsx_parts(const std::string& rows, const std::vector<std::string>& shared) {
  std::string sst =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?><sst "
      "xmlns=\"http://schemas.openxmlformats.org/spreadsheetml/2006/main\">";
  for (const auto& t : shared) sst += "<si><t>" + t + "</t></si>";
  sst += "</sst>";
  const std::string ns = "xmlns=\"http://schemas.openxmlformats.org/spreadsheetml/2006/main\"";
  const std::string rel =
      "xmlns:r=\"http://schemas.openxmlformats.org/officeDocument/2006/relationships\"";
  return {{"[Content_Types].xml",
           "<?xml version=\"1.0\" encoding=\"UTF-8\"?><Types "
           "xmlns=\"http://schemas.openxmlformats.org/package/2006/content-types\">"
           "<Default Extension=\"xml\" ContentType=\"application/xml\"/></Types>"},
          {"xl/workbook.xml",
           "<?xml version=\"1.0\" encoding=\"UTF-8\"?><workbook " + ns + " " + rel +
               "><sheets><sheet name=\"notes\" sheetId=\"1\" r:id=\"rId1\"/>"
               "<sheet name=\"signals\" sheetId=\"2\" r:id=\"rId2\"/></sheets></workbook>"},
          {"xl/_rels/workbook.xml.rels",
           "<?xml version=\"1.0\" encoding=\"UTF-8\"?><Relationships "
           "xmlns=\"http://schemas.openxmlformats.org/package/2006/relationships\">"
           "<Relationship Id=\"rId1\" Target=\"worksheets/sheet1.xml\"/>"
           "<Relationship Id=\"rId2\" Target=\"worksheets/sheet2.xml\"/></Relationships>"},
          {"xl/worksheets/sheet1.xml",
           "<?xml version=\"1.0\" encoding=\"UTF-8\"?><worksheet " + ns +
               "><sheetData><row r=\"1\"><c r=\"A1\" t=\"inlineStr\"><is><t>a "
               "synthetic record</t></is></c></row></sheetData></worksheet>"},
          {"xl/worksheets/sheet2.xml", "<?xml version=\"1.0\" encoding=\"UTF-8\"?><worksheet " +
                                           ns + "><sheetData>" + rows + "</sheetData></worksheet>"},
          {"xl/sharedStrings.xml", sst}};
}

// Zips `parts` into `file` (deflated, as Excel does).
inline void write_zip(const std::filesystem::path& file, const ZipParts& parts) {
  int err = 0;
  zip_t* z = zip_open(file.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &err);
  REQUIRE(z);
  for (const auto& [name, text] : parts) {
    zip_source_t* src = zip_source_buffer(z, text.data(), text.size(), 0);
    REQUIRE(zip_file_add(z, name.c_str(), src, ZIP_FL_OVERWRITE) >= 0);
  }
  REQUIRE(zip_close(z) == 0);  // the buffers are read here, while `parts` is alive
}

// The <row> elements of `csv_text`: the first line's fields as shared strings (appended to
// `shared`: the header), the others as numbers written as the CSV has them (17 digits).
inline std::string xlsx_rows(const std::string& csv_text, std::vector<std::string>& shared) {
  std::istringstream in(csv_text);
  std::string line, rows;
  for (std::size_t r = 1; std::getline(in, line); ++r) {
    rows += "<row r=\"" + std::to_string(r) + "\">";
    std::istringstream f(line);
    std::string v;
    for (char col = 'A'; std::getline(f, v, ','); ++col) {
      std::string ref(1, col);  // built by append: GCC 12 warns falsely on char + string
      ref += std::to_string(r);
      if (r == 1) {
        rows += "<c r=\"" + ref + "\" t=\"s\"><v>" + std::to_string(shared.size()) + "</v></c>";
        shared.push_back(v);
      } else {
        rows += "<c r=\"" + ref + "\"><v>" + v + "</v></c>";
      }
    }
    rows += "</row>";
  }
  return rows;
}

// A workbook whose sheet "signals" holds `csv_text` (xlsx_rows).
inline void write_xlsx(const std::filesystem::path& file, const std::string& csv_text) {
  std::vector<std::string> shared;
  const std::string rows = xlsx_rows(csv_text, shared);
  write_zip(file, xlsx_parts(rows, shared));
}

}  // namespace shpb_test
