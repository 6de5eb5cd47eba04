// .xlsx (Office Open XML: a zip of XML parts) read with libzip and expat, streamed: a part is
// inflated a chunk at a time straight into the XML parser, so memory holds the cells, never the
// XML. A workbook is untrusted input: the inflated size, the shared strings and the cells are
// bounded (below) before and while they are read, and a SIGINT/SIGTERM stops the read between
// chunks.
#include <expat.h>
#include <zip.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string_view>
#include <type_traits>
#include <vector>

#include "core/error.hpp"
#include "core/interrupt.hpp"
#include "core/spreadsheet_sheet.hpp"

namespace shpb::spreadsheet {
namespace {

namespace fs = std::filesystem;

// The XML a signal workbook needs: a full Excel sheet (1 048 576 rows) of 8 columns of 17-digit
// numbers is about 440 MB of XML (some 49 bytes a cell, 23 a row). The parts read (workbook,
// relationships, shared strings, the sheet) may inflate to this much in total: a part the zip
// directory declares larger is refused before anything is inflated (a zip bomb: 2.4 MB that
// inflates to gigabytes), and the inflated bytes are counted against the declared size and this
// budget as they come (a directory can lie).
constexpr zip_uint64_t kMaxXmlBytes = zip_uint64_t{512} << 20;
// Shared strings (the workbook's text cells): a signal sheet's text is its header and a few
// notes. One per row of a full sheet is far beyond that; a workbook declaring (uniqueCount) or
// holding more is refused before they are stored.
constexpr std::size_t kMaxSharedStrings = kMaxRows;
// Excel's limit of a cell's text, 32 767 characters, at up to 4 bytes each in UTF-8.
constexpr std::size_t kMaxCellTextBytes = 32767 * 4;
// Inflated per read: between chunks the read checks the budgets and for a SIGINT/SIGTERM (a chunk
// takes about a millisecond to inflate and parse).
constexpr std::size_t kChunkBytes = std::size_t{1} << 20;

struct ZipCloser {
  void operator()(zip_t* z) const { zip_discard(z); }
};

// The parts of one workbook, streamed within one budget of inflated bytes.
class Parts {
 public:
  Parts(zip_t* zip, const fs::path& file) : zip_(zip), file_(file) {}

  // Feeds part `name` to `sink` a chunk at a time; false if the workbook has no such part.
  bool read(const std::string& name, const std::function<void(const char*, std::size_t)>& sink) {
    zip_stat_t st;
    zip_stat_init(&st);
    if (zip_stat(zip_, name.c_str(), 0, &st) != 0) return false;
    if (!(st.valid & ZIP_STAT_SIZE))
      broken(file_, "part " + name + ": no size in the zip directory");
    if (st.size > budget_)
      throw input_error(file_.string(), "part " + name,
                        std::to_string(st.size) + " bytes uncompressed",
                        "beyond the " + std::to_string(kMaxXmlBytes) +
                            " bytes of XML a signal workbook is read up to (a zip bomb?)");
    std::unique_ptr<zip_file_t, int (*)(zip_file_t*)> f(zip_fopen(zip_, name.c_str(), 0),
                                                        zip_fclose);
    if (!f) broken(file_, "part " + name + " cannot be opened (" + zip_strerror(zip_) + ")");
    std::vector<char> buffer(kChunkBytes);
    zip_uint64_t total = 0;
    for (;;) {
      const zip_int64_t n = zip_fread(f.get(), buffer.data(), buffer.size());
      if (n < 0)
        broken(file_, "part " + name + " cannot be read (" + zip_file_strerror(f.get()) + ")");
      if (n == 0) break;
      total += static_cast<zip_uint64_t>(n);
      if (total > st.size)
        broken(file_, "part " + name + " inflates beyond the " + std::to_string(st.size) +
                          " bytes its zip directory declares");
      sink(buffer.data(), static_cast<std::size_t>(n));
      throw_if_interrupted();
    }
    if (total != st.size)
      broken(file_, "part " + name + " inflates to " + std::to_string(total) + " of the " +
                        std::to_string(st.size) + " bytes its zip directory declares");
    budget_ -= total;
    return true;
  }

 private:
  zip_t* zip_;
  const fs::path& file_;
  zip_uint64_t budget_ = kMaxXmlBytes;
};

// A tiny event parser: callbacks get the local element name (prefix stripped) and attributes. An
// exception thrown by a callback stops the parser and is rethrown by parse(), never unwound
// through expat's C frames.
class Xml {
 public:
  std::function<void(const std::string&, const char**)> start;
  std::function<void(const std::string&)> end;
  std::string text;  // character data since the last start tag
  bool keep_text = false;

  static std::string local(const char* name) {
    const char* colon = std::strrchr(name, ':');
    return colon ? colon + 1 : name;
  }

  // Parses part `part` of the workbook; false if there is no such part.
  bool parse(Parts& parts, const fs::path& file, const std::string& part) {
    std::unique_ptr<std::remove_pointer_t<XML_Parser>, void (*)(XML_Parser)> p(
        XML_ParserCreate(nullptr), XML_ParserFree);
    parser_ = p.get();
    XML_SetUserData(parser_, this);
    XML_SetElementHandler(parser_, on_start, on_end);
    XML_SetCharacterDataHandler(parser_, on_text);
    const auto feed = [&](const char* data, std::size_t size, bool last) {
      if (XML_Parse(parser_, data, static_cast<int>(size), last) == XML_STATUS_OK) return;
      if (error_) std::rethrow_exception(error_);
      broken(file, part + ": XML error at line " +
                       std::to_string(XML_GetCurrentLineNumber(parser_)) + ": " +
                       XML_ErrorString(XML_GetErrorCode(parser_)));
    };
    if (!parts.read(part, [&](const char* data, std::size_t size) { feed(data, size, false); }))
      return false;
    feed(nullptr, 0, true);
    return true;
  }

 private:
  template <class F>
  static void guarded(void* user, F&& f) {
    auto* x = static_cast<Xml*>(user);
    if (x->error_) return;
    try {
      f(*x);
    } catch (...) {
      x->error_ = std::current_exception();
      XML_StopParser(x->parser_, XML_FALSE);
    }
  }
  static void on_start(void* u, const char* name, const char** attrs) {
    guarded(u, [&](Xml& x) {
      x.text.clear();
      if (x.start) x.start(local(name), attrs);
    });
  }
  static void on_end(void* u, const char* name) {
    guarded(u, [&](Xml& x) {
      if (x.end) x.end(local(name));
    });
  }
  static void on_text(void* u, const char* s, int len) {
    guarded(u, [&](Xml& x) {
      if (!x.keep_text) return;
      if (x.text.size() + static_cast<std::size_t>(len) > kMaxCellTextBytes)
        throw std::length_error("a text of more than 32767 characters");
      x.text.append(s, static_cast<std::size_t>(len));
    });
  }

  XML_Parser parser_ = nullptr;
  std::exception_ptr error_;
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

// The workbook's shared strings (the text cells), if it has them.
std::vector<std::string> shared_strings(Parts& parts, const fs::path& file) {
  const std::string part = "xl/sharedStrings.xml";
  std::vector<std::string> shared;
  Xml x;
  x.keep_text = true;
  std::string current;
  const auto too_many = [&](const std::string& count) {
    return input_error(file.string(), "part " + part, count + " shared strings",
                       "beyond the " + std::to_string(kMaxSharedStrings) +
                           " a signal workbook is read with (one per row of a full sheet)");
  };
  x.start = [&](const std::string& el, const char** a) {
    if (el == "si") current.clear();
    if (el == "sst")
      if (const char* n = attribute(a, "uniqueCount"))
        if (std::strtoull(n, nullptr, 10) > kMaxSharedStrings) throw too_many(n);
  };
  x.end = [&](const std::string& el) {
    if (el == "t") {
      if (current.size() + x.text.size() > kMaxCellTextBytes)
        throw std::length_error("a text of more than 32767 characters");
      current += x.text;
    }
    if (el == "si") {
      if (shared.size() == kMaxSharedStrings)
        throw too_many("more than " + std::to_string(kMaxSharedStrings));
      shared.push_back(current);
    }
  };
  try {
    x.parse(parts, file, part);
  } catch (const std::length_error& e) {
    broken(file, part + ": " + e.what());
  }
  return shared;
}

// The sheet to read and its part: `sheet` by name, else the first worksheet.
struct ChosenSheet {
  std::string name, part;
};
ChosenSheet chosen_sheet(Parts& parts, const fs::path& file, const std::string& sheet) {
  // Sheet names → relationship ids → parts.
  std::vector<std::pair<std::string, std::string>> sheets;  // name, r:id
  Xml wb;
  wb.start = [&](const std::string& el, const char** a) {
    if (el != "sheet") return;
    const char* name = attribute(a, "name");
    const char* id = attribute(a, "id");
    if (name && id) sheets.emplace_back(name, id);
  };
  std::map<std::string, std::string> targets;
  std::set<std::string> charts;  // r:ids of chart sheets (a chart, no cells)
  Xml rl;
  rl.start = [&](const std::string& el, const char** a) {
    if (el != "Relationship") return;
    const char* id = attribute(a, "Id");
    const char* target = attribute(a, "Target");
    const char* type = attribute(a, "Type");
    if (id && target) targets[id] = target;
    if (id && type && std::string_view(type).ends_with("/chartsheet")) charts.insert(id);
  };
  if (!wb.parse(parts, file, "xl/workbook.xml") ||
      !rl.parse(parts, file, "xl/_rels/workbook.xml.rels"))
    broken(file, "no xl/workbook.xml");
  if (sheets.empty()) broken(file, "a workbook without sheets");
  // By default the first worksheet: a chart sheet (a plot saved in front of the data) holds no
  // cells.
  const auto worksheet = [&](const auto& s) { return !charts.contains(s.second); };
  const auto worksheet_names = [&] {
    std::vector<std::string> names;
    for (const auto& s : sheets)
      if (worksheet(s)) names.push_back(s.first);
    return names_text(names);
  };
  auto chosen = std::find_if(sheets.begin(), sheets.end(), worksheet);
  if (chosen == sheets.end()) broken(file, "a workbook of chart sheets only");
  if (!sheet.empty()) {
    chosen =
        std::find_if(sheets.begin(), sheets.end(), [&](const auto& s) { return s.first == sheet; });
    if (chosen == sheets.end()) {
      std::vector<std::string> names;
      for (const auto& s : sheets) names.push_back(s.first);
      throw input_error(file.string(), "sheet", "\"" + sheet + "\"",
                        "no such sheet; the workbook has " + names_text(names));
    }
    if (!worksheet(*chosen))
      throw input_error(file.string(), "sheet", "\"" + sheet + "\"",
                        "a chart sheet, which holds no cells; the workbook's worksheets are " +
                            worksheet_names());
  }
  const std::string& target = targets[chosen->second];
  return {chosen->first, target.rfind('/', 0) == 0 ? target.substr(1) : "xl/" + target};
}

}  // namespace

DelimitedText read_xlsx(const fs::path& file, const std::string& sheet) {
  int err = 0;
  std::unique_ptr<zip_t, ZipCloser> zip(zip_open(file.c_str(), ZIP_RDONLY, &err));
  if (!zip) {
    zip_error_t e;
    zip_error_init_with_code(&e, err);
    const std::string reason = zip_error_strerror(&e);
    zip_error_fini(&e);
    broken(file, "not a zip archive (" + reason + ")");
  }
  Parts parts(zip.get(), file);
  const ChosenSheet chosen = chosen_sheet(parts, file, sheet);
  const std::string& part = chosen.part;
  const std::vector<std::string> shared = shared_strings(parts, file);

  Sheet out(file);
  std::size_t row = 0, column = 0, next_row = 1;
  std::string type, value, formula;
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
      formula.clear();
      in_cell = true;
    }
  };
  x.end = [&](const std::string& el) {
    if (!in_cell) return;
    if (el == "v" || el == "t") {
      if (value.size() + x.text.size() > kMaxCellTextBytes)
        throw std::length_error("a text of more than 32767 characters");
      value += x.text;
    }
    // A formula's text, kept for a cell whose value the workbook does not hold (a program that
    // writes formulas without computing them): "=A2+1E-7" is then what the cell reads as, named
    // by the reader, never an empty field.
    // Built by push_back and append of a view: GCC 12 warns falsely (-Wrestrict) on "=" + text.
    if (el == "f") {
      formula.clear();
      formula.push_back('=');
      formula.append(x.text.empty() ? std::string_view("(shared formula)")
                                    : std::string_view(x.text));
    }
    if (el == "c") {
      if (value.empty()) value = formula;
      if (type == "s") {
        char* end = nullptr;
        const unsigned long i = std::strtoul(value.c_str(), &end, 10);
        if (value.empty() || *end || i >= shared.size())
          broken(file, part + ": shared string index \"" + value + "\"");
        value = shared[i];
      }
      // A TRUE/FALSE cell is no sample: read as text it would pass for a header, as a number
      // for 1 or 0.
      if (type == "b")
        throw input_error(file.string(),
                          "sheet \"" + chosen.name + "\", cell " + cell_name(row, column),
                          value == "1"   ? "TRUE"
                          : value == "0" ? "FALSE"
                                         : "\"" + value + "\"",
                          "a boolean cell; expected a number (or a header's text)");
      out.set(row, column, value);
      ++column;
      in_cell = false;
    }
  };
  try {
    if (!x.parse(parts, file, part))
      broken(file, "sheet \"" + chosen.name + "\" has no part " + part);
  } catch (const std::length_error& e) {
    broken(file, part + ": " + e.what());
  }
  return std::move(out).text();
}

}  // namespace shpb::spreadsheet
