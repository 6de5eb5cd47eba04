#include "core/csv_writer.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>

namespace shpb {

std::string format_double(double value) {
  char buffer[32];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, end);
}

CsvWriter::CsvWriter(const std::filesystem::path& file, const std::vector<std::string>& header)
    : path_(file), columns_(header.size()) {
  file_ = std::fopen(file.c_str(), "w");
  if (!file_) throw std::runtime_error(file.string() + ": cannot be written");
  // Output files run to megabytes (field.csv): large writes, few system calls.
  std::setvbuf(file_, buffer_.data(), _IOFBF, buffer_.size());
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (i) std::fputc(',', file_);
    std::fputs(header[i].c_str(), file_);
  }
  std::fputc('\n', file_);
}

CsvWriter::~CsvWriter() {
  if (file_) std::fclose(file_);
}

void CsvWriter::row(std::span<const double> values) { row({}, 0, values); }

void CsvWriter::row(std::string_view leading, std::size_t leading_columns,
                    std::span<const double> values) {
  if (leading_columns + values.size() != columns_)
    throw std::logic_error(path_.string() + ": row has " +
                           std::to_string(leading_columns + values.size()) + " values for " +
                           std::to_string(columns_) + " columns");
  line_.assign(leading);
  char buffer[32];
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i || leading_columns) line_.push_back(',');
    if (!std::isfinite(values[i]))
      throw std::logic_error(path_.string() + ": refusing to write a non-finite value");
    auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, values[i]);
    line_.append(buffer, end);
  }
  line_.push_back('\n');
  std::fwrite(line_.data(), 1, line_.size(), file_);
}

}  // namespace shpb
