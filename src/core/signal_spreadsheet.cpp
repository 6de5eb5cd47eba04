#include "core/signal_spreadsheet.hpp"

#include <fcntl.h>
#include <freexl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <string_view>
#include <vector>

#include "core/error.hpp"
#include "core/interrupt.hpp"
#include "core/spreadsheet_sheet.hpp"

#if defined(__SANITIZE_ADDRESS__)
#define SHPB_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SHPB_ASAN 1
#endif
#endif
#if SHPB_ASAN
#include <sanitizer/common_interface_defs.h>
#endif

namespace shpb {
namespace spreadsheet {

void broken(const std::filesystem::path& file, const std::string& what) {
  throw input_error(file.string(), "", what, "expected an Excel workbook (.xlsx or .xls)");
}

std::string names_text(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "\"" : ", \"") + n + "\"";
  return s;
}

std::string cell_name(std::size_t row, std::size_t column) {
  std::string letters;
  for (std::size_t c = column + 1; c > 0; c = (c - 1) / 26)
    letters.insert(letters.begin(), static_cast<char>('A' + (c - 1) % 26));
  return letters + std::to_string(row);
}

void Sheet::set(std::size_t row, std::size_t column, std::string value) {
  if (row < 1 || row > kMaxRows || column >= kMaxColumns)
    throw input_error(file_.string(), "row " + std::to_string(row),
                      "column " + std::to_string(column + 1),
                      "beyond Excel's 1048576 rows x 16384 columns");
  auto& fields = rows_[row];
  if (fields.size() <= column) {
    // Every field up to the cell is stored: count them all (one cell in column XFD of each row
    // would otherwise take 16 384 fields a row).
    cells_ += column + 1 - fields.size();
    if (cells_ > kMaxCells)
      throw input_error(file_.string(), "", "more than " + std::to_string(kMaxCells) + " cells",
                        "beyond a signal sheet (1048576 rows of 16 columns)");
    fields.resize(column + 1);
  }
  fields[column] = std::move(value);
}

DelimitedText Sheet::text() && {
  DelimitedText t;
  t.file = file_;
  // The text's rows view one buffer of every cell, as a CSV's view its bytes.
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
  std::size_t begin = 0;
  for (const auto& [row, end] : rows) {
    std::vector<std::string_view> cells;
    for (std::size_t k = begin; k < end; ++k)
      cells.emplace_back(bytes->data() + offsets[k].first, offsets[k].second);
    t.rows.add_cells(row, std::move(cells));
    begin = end;
  }
  t.bytes = std::move(bytes);
  detect_decimal_comma(t);  // text cells such as "0,25" (a German CSV pasted as text)
  if (t.rows.empty())
    throw input_error(file_.string(), "", "empty sheet", "expected rows of numbers after a header");
  return t;
}

}  // namespace spreadsheet

namespace {

using spreadsheet::broken;
using spreadsheet::Sheet;

std::string lower_extension(const std::filesystem::path& file) {
  std::string e = file.extension().string();
  for (auto& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

// ---- .xls ----
//
// FreeXL (a C library, not built with shpb's sanitizers) reads BIFF records and the OLE2
// compound file around them with offsets taken from the file; slightly corrupted workbooks have
// crashed it. The .xls is therefore read in a child process: a crash there is a message and
// exit 2 here, whatever the corruption. Validating the structure first would have to repeat
// FreeXL's whole parser to be sure; the child costs one fork per workbook (about a millisecond).

// Every OLE2 compound file (the container of BIFF5/8 workbooks, the only ones FreeXL reads)
// starts with these bytes: anything else is refused without starting the reader.
constexpr unsigned char kOle2Signature[8] = {0xD0, 0xCF, 0x11, 0xE0, 0xA1, 0xB1, 0x1A, 0xE1};
// The parent polls for a SIGINT/SIGTERM this often while the child reads.
constexpr int kPollMilliseconds = 50;

// The child's answer on the pipe: one status byte, then either the error message or the cells as
// records of (row, column, size, bytes) in native byte order.
enum : char { kCells = 'c', kInputError = 'e' };

void put(std::string& out, std::uint64_t v) { out.append(reinterpret_cast<const char*>(&v), 8); }

// The cells of the sheet, read with FreeXL in this process: kCells + records. BIFF8 holds at most
// 65 536 rows × 256 columns (spreadsheet::kMaxCells): the parent's Sheet checks the limits.
std::string read_xls_cells(const std::filesystem::path& file, const std::string& sheet) {
  std::string out(1, kCells);
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
                      "no such sheet; the workbook has " + spreadsheet::names_text(names));
  unsigned int rows = 0;
  unsigned short columns = 0;
  if (freexl_select_active_worksheet(h, chosen) != FREEXL_OK ||
      freexl_worksheet_dimensions(h, &rows, &columns) != FREEXL_OK)
    broken(file, "sheet \"" + names[chosen] + "\" cannot be read");
  for (unsigned int r = 0; r < rows; ++r)
    for (unsigned short c = 0; c < columns; ++c) {
      FreeXL_CellValue cell;
      if (freexl_get_cell_value(h, r, c, &cell) != FREEXL_OK) continue;
      char buf[40];
      std::string_view value;
      switch (cell.type) {
        case FREEXL_CELL_INT:
          value = std::string_view(buf, static_cast<std::size_t>(std::snprintf(
                                            buf, sizeof buf, "%d", cell.value.int_value)));
          break;
        case FREEXL_CELL_DOUBLE:
          value = std::string_view(buf, static_cast<std::size_t>(std::snprintf(
                                            buf, sizeof buf, "%.17g", cell.value.double_value)));
          break;
        case FREEXL_CELL_TEXT:
        case FREEXL_CELL_SST_TEXT:
          value = cell.value.text_value ? cell.value.text_value : "";
          break;
        default:
          continue;
      }
      put(out, r + 1);
      put(out, c);
      put(out, value.size());
      out.append(value);
    }
  return out;
}

bool write_all(int fd, const std::string& data) {
  for (std::size_t done = 0; done < data.size();) {
    const ssize_t n = ::write(fd, data.data() + done, data.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

// The child: reads, answers on `fd` and ends without running the parent's exit handlers.
[[noreturn]] void xls_child(int fd, const std::filesystem::path& file, const std::string& sheet) {
  // A SIGINT/SIGTERM ends the child at once (the parent stops it too).
  ::signal(SIGINT, SIG_DFL);
  ::signal(SIGTERM, SIG_DFL);
#if SHPB_ASAN
  // A sanitizer report in the child is FreeXL's, contained here: a fuzzer's death callback
  // inherited from the parent must not record it as a crash of the parent's input.
  __sanitizer_set_death_callback(nullptr);
#endif
  // The child answers through `fd` only: what FreeXL (or a sanitizer report of its fault) prints
  // is not shpb's one-line message, so its stderr goes nowhere.
  if (const int null = ::open("/dev/null", O_WRONLY); null >= 0) ::dup2(null, STDERR_FILENO);
  std::string answer;
  try {
    answer = read_xls_cells(file, sheet);
  } catch (const InputError& e) {
    answer = std::string(1, kInputError) + e.what();
  } catch (const std::exception& e) {
    answer = std::string(1, kInputError) + file.string() + ": " + e.what() +
             ": expected an Excel workbook (.xlsx or .xls)";
  }
  ::_exit(write_all(fd, answer) ? 0 : 1);
}

// Runs the child and collects its answer; a SIGINT/SIGTERM stops it (Interrupted).
std::string run_xls_child(const std::filesystem::path& file, const std::string& sheet) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0)
    throw input_error(file.string(), "", "", "cannot be read (no pipe for the .xls reader)");
  std::fflush(nullptr);  // nothing buffered is written twice
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw input_error(file.string(), "", "", "cannot be read (no process for the .xls reader)");
  }
  if (pid == 0) {
    ::close(fds[0]);
    xls_child(fds[1], file, sheet);
  }
  ::close(fds[1]);
  std::string answer;
  bool stopped = false;
  char buffer[1 << 16];
  for (;;) {
    if (interrupted()) {
      ::kill(pid, SIGKILL);
      stopped = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, kPollMilliseconds);
    if (ready < 0 && errno != EINTR) break;
    if (ready <= 0) continue;
    const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    answer.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (stopped) throw Interrupted();
  if (WIFSIGNALED(status))
    broken(file, "the .xls reader (FreeXL) failed on this file (signal " +
                     std::to_string(WTERMSIG(status)) + ")");
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || answer.empty())
    broken(file, "the .xls reader (FreeXL) failed on this file");
  return answer;
}

DelimitedText read_xls(const std::filesystem::path& file, const std::string& sheet) {
  {
    unsigned char head[sizeof kOle2Signature] = {};
    std::ifstream in(file, std::ios::binary);
    in.read(reinterpret_cast<char*>(head), sizeof head);
    if (!in || std::memcmp(head, kOle2Signature, sizeof head) != 0)
      broken(file, "not an .xls workbook (no OLE2 compound-file signature)");
  }
  const std::string answer = run_xls_child(file, sheet);
  if (answer[0] == kInputError) throw InputError(answer.substr(1));
  if (answer[0] != kCells) broken(file, "the .xls reader (FreeXL) failed on this file");
  Sheet out(file);
  std::size_t at = 1;
  const auto take = [&] {
    std::uint64_t v = 0;
    if (answer.size() - at < 8) broken(file, "the .xls reader (FreeXL) failed on this file");
    std::memcpy(&v, answer.data() + at, 8);
    at += 8;
    return v;
  };
  while (at < answer.size()) {
    const std::uint64_t row = take(), column = take(), size = take();
    if (answer.size() - at < size) broken(file, "the .xls reader (FreeXL) failed on this file");
    out.set(row, column, answer.substr(at, size));
    throw_if_interrupted();
    at += size;
  }
  return std::move(out).text();
}

}  // namespace

bool is_spreadsheet(const std::filesystem::path& file) {
  const auto e = lower_extension(file);
  return e == ".xlsx" || e == ".xls";
}

std::string empty_cell_cause(const std::filesystem::path& file) {
  return lower_extension(file) == ".xls"
             ? " (the .xls reader gives no formula's value: a cell holding a formula reads "
               "empty; save the workbook as .xlsx, or paste its values)"
             : "";
}

DelimitedText read_spreadsheet(const std::filesystem::path& file, const std::string& sheet) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw input_error(file.string(), "", "", "cannot be read");
  return lower_extension(file) == ".xlsx" ? spreadsheet::read_xlsx(file, sheet)
                                          : read_xls(file, sheet);
}

}  // namespace shpb
