#include "core/csv_writer.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <stdexcept>

#include "core/checked_write.hpp"
#include "core/interrupt.hpp"

namespace shpb {

std::string format_double(double value) {
  char buffer[32];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, end);
}

namespace {
// A cell's number: a subnormal (|x| < 2.2e-308: a wave front's underflowing foot, -1e-323) is
// written as 0: no strain, stress or time is that small, and readers refuse it (C++'s std::stod,
// spreadsheets that hold doubles only down to 2.2e-308).
double cell_value(double value) { return std::fpclassify(value) == FP_SUBNORMAL ? 0.0 : value; }
}  // namespace

std::string format_field(double value) {
  return std::isfinite(value) ? format_double(cell_value(value)) : std::string();
}

std::string quote_cell(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

CsvWriter::CsvWriter(const std::filesystem::path& file, const std::vector<std::string>& header)
    : path_(file), columns_(header.size()) {
  file_ = std::fopen(file.c_str(), "w");
  if (!file_) throw_write_error(file, errno);
  // Output files run to megabytes (field.csv): large writes, few system calls.
  std::setvbuf(file_, buffer_.data(), _IOFBF, buffer_.size());
  std::string line;
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (i) line.push_back(',');
    line += header[i];
  }
  line.push_back('\n');
  write(line);
}

CsvWriter::~CsvWriter() {
  if (file_) std::fclose(file_);
}

void CsvWriter::write(const std::string& text) {
  // Files run to millions of rows (field.csv): a SIGINT/SIGTERM stops the write within a second.
  constexpr unsigned kInterruptPollRows = 1u << 14;
  if (++rows_ % kInterruptPollRows == 0) throw_if_interrupted();
  errno = 0;
  if (std::fwrite(text.data(), 1, text.size(), file_) != text.size())
    throw_write_error(path_, errno ? errno : EIO);
}

void CsvWriter::close() {
  if (!file_) return;
  errno = 0;
  const bool flushed = std::fflush(file_) == 0 && !std::ferror(file_);
  const int flush_errno = errno;
  const int closed = std::fclose(file_);
  file_ = nullptr;
  if (!flushed) throw_write_error(path_, flush_errno ? flush_errno : EIO);
  if (closed != 0) throw_write_error(path_, errno ? errno : EIO);
}

void CsvWriter::row(std::span<const double> values) { row({}, 0, values); }

void CsvWriter::row(std::span<const std::string> cells) {
  if (cells.size() != columns_)
    throw std::logic_error(path_.string() + ": row has " + std::to_string(cells.size()) +
                           " cells for " + std::to_string(columns_) + " columns");
  if (!file_) throw std::logic_error(path_.string() + ": row written after close()");
  line_.clear();
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (i) line_.push_back(',');
    line_ += cells[i];
  }
  line_.push_back('\n');
  write(line_);
}

void CsvWriter::row(std::string_view leading, std::size_t leading_columns,
                    std::span<const double> values) {
  row(leading, leading_columns, values, {}, 0);
}

void CsvWriter::row(std::span<const double> values, std::string_view trailing) {
  row({}, 0, values, trailing,
      static_cast<std::size_t>(std::count(trailing.begin(), trailing.end(), ',')));
}

void CsvWriter::row(std::string_view leading, std::size_t leading_columns,
                    std::span<const double> values, std::string_view trailing,
                    std::size_t trailing_columns) {
  if (leading_columns + values.size() + trailing_columns != columns_)
    throw std::logic_error(path_.string() + ": row has " +
                           std::to_string(leading_columns + values.size() + trailing_columns) +
                           " values for " + std::to_string(columns_) + " columns");
  if (!file_) throw std::logic_error(path_.string() + ": row written after close()");
  line_.assign(leading);
  char buffer[32];
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i || leading_columns) line_.push_back(',');
    if (!std::isfinite(values[i]))
      throw std::logic_error(path_.string() + ": refusing to write a non-finite value");
    auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, cell_value(values[i]));
    line_.append(buffer, end);
  }
  line_.append(trailing);
  line_.push_back('\n');
  write(line_);
}

}  // namespace shpb
