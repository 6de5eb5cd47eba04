#include "core/signal_spreadsheet.hpp"

#include <expat.h>
#include <freexl.h>
#include <zip.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <type_traits>
#include <vector>

#include "core/error.hpp"

namespace shpb {
namespace {

// Excel's own limits (Excel 2007+: 1 048 576 rows × 16 384 columns): anything beyond is refused
// before rows are allocated.
constexpr std::size_t kMaxRows = 1048576;
constexpr std::size_t kMaxColumns = 16384;
// A part of the zip larger than this is no signal sheet (1 GiB of XML).
constexpr zip_uint64_t kMaxPartBytes = zip_uint64_t{1} << 30;

std::string lower_extension(const std::filesystem::path& file) {
  std::string e = file.extension().string();
  for (auto& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

[[noreturn]] void broken(const std::filesystem::path& file, const std::string& what) {
  throw input_error(file.string(), "", what, "expected an Excel workbook (.xlsx or .xls)");
}

std::string names_text(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "\"" : ", \"") + n + "\"";
  return s;
}

// Rows of a sheet: row number → fields by column.
class Sheet {
 public:
  explicit Sheet(const std::filesystem::path& file) : file_(file) {}
  void set(std::size_t row, std::size_t column, std::string value) {
    if (row < 1 || row > kMaxRows || column >= kMaxColumns)
      throw input_error(file_.string(), "row " + std::to_string(row),
                        "column " + std::to_string(column + 1),
                        "beyond Excel's 1048576 rows x 16384 columns");
    auto& fields = rows_[row];
    if (fields.size() <= column) fields.resize(column + 1);
    fields[column] = std::move(value);
  }
  DelimitedText text() && {
    DelimitedText t;
    t.file = file_;
    // The text's rows view one buffer of every cell and one list of every field, as a CSV's do.
    auto bytes = std::make_shared<std::string>();
    std::vector<std::pair<std::size_t, std::size_t>> offsets;  // each field's start and size
    std::vector<std::pair<std::size_t, std::size_t>> rows;     // row number, fields' end
    for (const auto& [row, fields] : rows_) {
      bool blank = true;
      for (const auto& f : fields) blank = blank && f.empty();
      if (blank) continue;
      for (const auto& f : fields) {
        offsets.emplace_back(bytes->size(), f.size());
        *bytes += f;
      }
      rows.emplace_back(row, offsets.size());
    }
    auto all = std::make_shared<std::vector<std::string_view>>();
    all->reserve(offsets.size());
    for (const auto& [start, size] : offsets) all->emplace_back(bytes->data() + start, size);
    std::size_t begin = 0;
    for (const auto& [row, end] : rows) {
      t.rows.push_back({row, std::span<const std::string_view>(all->data() + begin, end - begin)});
      begin = end;
    }
    t.bytes = std::move(bytes);
    t.all_fields = std::move(all);
    if (t.rows.empty())
      throw input_error(file_.string(), "", "empty sheet",
                        "expected rows of numbers after a header");
    return t;
  }

 private:
  std::filesystem::path file_;
  std::map<std::size_t, std::vector<std::string>> rows_;
};

// ---- .xlsx ----

struct ZipCloser {
  void operator()(zip_t* z) const { zip_discard(z); }
};

std::optional<std::string> zip_part(zip_t* zip, const std::filesystem::path& file,
                                    const std::string& name) {
  zip_stat_t st;
  zip_stat_init(&st);
  if (zip_stat(zip, name.c_str(), 0, &st) != 0) return std::nullopt;
  if (!(st.valid & ZIP_STAT_SIZE) || st.size > kMaxPartBytes)
    broken(file, "part " + name + " of " + std::to_string(st.size) + " bytes");
  std::unique_ptr<zip_file_t, int (*)(zip_file_t*)> f(zip_fopen(zip, name.c_str(), 0), zip_fclose);
  if (!f) broken(file, "part " + name + " cannot be opened");
  std::string data(st.size, '\0');
  if (zip_fread(f.get(), data.data(), st.size) != static_cast<zip_int64_t>(st.size))
    broken(file, "part " + name + " cannot be read");
  return data;
}

// A tiny event parser: callbacks get the local element name (prefix stripped) and attributes.
struct Xml {
  std::function<void(const std::string&, const char**)> start;
  std::function<void(const std::string&)> end;
  std::string text;  // character data since the last start tag
  bool keep_text = false;

  static std::string local(const char* name) {
    const char* colon = std::strrchr(name, ':');
    return colon ? colon + 1 : name;
  }
  void parse(const std::string& data, const std::filesystem::path& file, const std::string& part) {
    std::unique_ptr<std::remove_pointer_t<XML_Parser>, void (*)(XML_Parser)> p(
        XML_ParserCreate(nullptr), XML_ParserFree);
    XML_SetUserData(p.get(), this);
    XML_SetElementHandler(
        p.get(),
        [](void* u, const char* name, const char** attrs) {
          auto* x = static_cast<Xml*>(u);
          x->text.clear();
          if (x->start) x->start(local(name), attrs);
        },
        [](void* u, const char* name) {
          auto* x = static_cast<Xml*>(u);
          if (x->end) x->end(local(name));
        });
    XML_SetCharacterDataHandler(p.get(), [](void* u, const char* s, int len) {
      auto* x = static_cast<Xml*>(u);
      if (x->keep_text) x->text.append(s, static_cast<std::size_t>(len));
    });
    if (XML_Parse(p.get(), data.data(), static_cast<int>(data.size()), 1) != XML_STATUS_OK)
      broken(file, part + ": XML error at line " +
                       std::to_string(XML_GetCurrentLineNumber(p.get())) + ": " +
                       XML_ErrorString(XML_GetErrorCode(p.get())));
  }
};

const char* attribute(const char** attrs, const char* name) {
  for (std::size_t i = 0; attrs[i]; i += 2)
    if (Xml::local(attrs[i]) == name) return attrs[i + 1];
  return nullptr;
}

// "BC12" → column 54 (0-based) and row 12.
bool cell_place(const char* ref, std::size_t& row, std::size_t& column) {
  std::size_t c = 0, i = 0;
  while (std::isalpha(static_cast<unsigned char>(ref[i]))) {
    c = c * 26 +
        static_cast<std::size_t>(std::toupper(static_cast<unsigned char>(ref[i])) - 'A' + 1);
    if (c > kMaxColumns) return false;
    ++i;
  }
  if (c == 0 || !std::isdigit(static_cast<unsigned char>(ref[i]))) return false;
  row = std::strtoul(ref + i, nullptr, 10);
  column = c - 1;
  return true;
}

DelimitedText read_xlsx(const std::filesystem::path& file, const std::string& sheet) {
  int err = 0;
  std::unique_ptr<zip_t, ZipCloser> zip(zip_open(file.c_str(), ZIP_RDONLY, &err));
  if (!zip) broken(file, "not a zip archive (libzip error " + std::to_string(err) + ")");
  const auto workbook = zip_part(zip.get(), file, "xl/workbook.xml");
  const auto rels = zip_part(zip.get(), file, "xl/_rels/workbook.xml.rels");
  if (!workbook || !rels) broken(file, "no xl/workbook.xml");
  // Sheet names → relationship ids → parts.
  std::vector<std::pair<std::string, std::string>> sheets;  // name, r:id
  Xml wb;
  wb.start = [&](const std::string& el, const char** a) {
    if (el != "sheet") return;
    const char* name = attribute(a, "name");
    const char* id = attribute(a, "id");
    if (name && id) sheets.emplace_back(name, id);
  };
  wb.parse(*workbook, file, "xl/workbook.xml");
  std::map<std::string, std::string> targets;
  Xml rl;
  rl.start = [&](const std::string& el, const char** a) {
    if (el != "Relationship") return;
    const char* id = attribute(a, "Id");
    const char* target = attribute(a, "Target");
    if (id && target) targets[id] = target;
  };
  rl.parse(*rels, file, "xl/_rels/workbook.xml.rels");
  if (sheets.empty()) broken(file, "a workbook without sheets");
  auto chosen = sheets.begin();
  if (!sheet.empty()) {
    chosen =
        std::find_if(sheets.begin(), sheets.end(), [&](const auto& s) { return s.first == sheet; });
    if (chosen == sheets.end()) {
      std::vector<std::string> names;
      for (const auto& s : sheets) names.push_back(s.first);
      throw input_error(file.string(), "sheet", "\"" + sheet + "\"",
                        "no such sheet; the workbook has " + names_text(names));
    }
  }
  std::string part = targets[chosen->second];
  part = part.rfind('/', 0) == 0 ? part.substr(1) : "xl/" + part;
  const auto data = zip_part(zip.get(), file, part);
  if (!data) broken(file, "sheet \"" + chosen->first + "\" has no part " + part);

  std::vector<std::string> shared;
  if (const auto ss = zip_part(zip.get(), file, "xl/sharedStrings.xml")) {
    Xml x;
    x.keep_text = true;
    std::string current;
    x.start = [&](const std::string& el, const char**) {
      if (el == "si") current.clear();
    };
    x.end = [&](const std::string& el) {
      if (el == "t") current += x.text;
      if (el == "si") shared.push_back(current);
    };
    x.parse(*ss, file, "xl/sharedStrings.xml");
  }

  Sheet out(file);
  std::size_t row = 0, column = 0, next_row = 1;
  std::string type, value;
  bool in_cell = false;
  Xml x;
  x.keep_text = true;
  x.start = [&](const std::string& el, const char** a) {
    if (el == "row") {
      const char* r = attribute(a, "r");
      row = r ? std::strtoul(r, nullptr, 10) : next_row;
      next_row = row + 1;
      column = 0;
    } else if (el == "c") {
      const char* ref = attribute(a, "r");
      std::size_t r = row;
      if (ref && !cell_place(ref, r, column))
        broken(file, part + ": cell reference \"" + ref + "\"");
      row = r;
      const char* t = attribute(a, "t");
      type = t ? t : "n";
      value.clear();
      in_cell = true;
    }
  };
  x.end = [&](const std::string& el) {
    if (!in_cell) return;
    if (el == "v" || el == "t") value += x.text;
    if (el == "c") {
      if (type == "s") {
        char* end = nullptr;
        const unsigned long i = std::strtoul(value.c_str(), &end, 10);
        if (value.empty() || *end || i >= shared.size())
          broken(file, part + ": shared string index \"" + value + "\"");
        value = shared[i];
      }
      out.set(row, column, value);
      ++column;
      in_cell = false;
    }
  };
  x.parse(*data, file, part);
  return std::move(out).text();
}

// ---- .xls ----

DelimitedText read_xls(const std::filesystem::path& file, const std::string& sheet) {
  const void* h = nullptr;
  if (freexl_open(file.c_str(), &h) != FREEXL_OK) broken(file, "not a readable .xls (BIFF) file");
  std::unique_ptr<const void, int (*)(const void*)> handle(h, freexl_close);
  unsigned int count = 0;
  if (freexl_get_info(h, FREEXL_BIFF_SHEET_COUNT, &count) != FREEXL_OK || count == 0)
    broken(file, "a workbook without sheets");
  std::vector<std::string> names;
  unsigned short chosen = 0;
  bool found = sheet.empty();
  for (unsigned short i = 0; i < count; ++i) {
    const char* name = nullptr;
    freexl_get_worksheet_name(h, i, &name);
    names.push_back(name ? name : "");
    if (!found && names.back() == sheet) chosen = i, found = true;
  }
  if (!found)
    throw input_error(file.string(), "sheet", "\"" + sheet + "\"",
                      "no such sheet; the workbook has " + names_text(names));
  unsigned int rows = 0;
  unsigned short columns = 0;
  if (freexl_select_active_worksheet(h, chosen) != FREEXL_OK ||
      freexl_worksheet_dimensions(h, &rows, &columns) != FREEXL_OK)
    broken(file, "sheet \"" + names[chosen] + "\" cannot be read");
  Sheet out(file);
  for (unsigned int r = 0; r < rows; ++r)
    for (unsigned short c = 0; c < columns; ++c) {
      FreeXL_CellValue cell;
      if (freexl_get_cell_value(h, r, c, &cell) != FREEXL_OK) continue;
      char buf[40];
      switch (cell.type) {
        case FREEXL_CELL_INT:
          std::snprintf(buf, sizeof buf, "%d", cell.value.int_value);
          out.set(r + 1, c, buf);
          break;
        case FREEXL_CELL_DOUBLE:
          std::snprintf(buf, sizeof buf, "%.17g", cell.value.double_value);
          out.set(r + 1, c, buf);
          break;
        case FREEXL_CELL_TEXT:
        case FREEXL_CELL_SST_TEXT:
          out.set(r + 1, c, cell.value.text_value ? cell.value.text_value : "");
          break;
        default:
          break;
      }
    }
  return std::move(out).text();
}

}  // namespace

bool is_spreadsheet(const std::filesystem::path& file) {
  const auto e = lower_extension(file);
  return e == ".xlsx" || e == ".xls";
}

DelimitedText read_spreadsheet(const std::filesystem::path& file, const std::string& sheet) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw input_error(file.string(), "", "", "cannot be read");
  return lower_extension(file) == ".xlsx" ? read_xlsx(file, sheet) : read_xls(file, sheet);
}

}  // namespace shpb
