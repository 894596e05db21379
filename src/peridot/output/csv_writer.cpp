#include "peridot/output/csv_writer.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "peridot/core/error.hpp"

namespace peridot {

namespace {

std::string quoted(const std::string& name) {
  if (name.find_first_of(",\"\r\n") == std::string::npos) return name;
  std::string out = "\"";
  for (char c : name) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + '"';
}

[[noreturn]] void throw_errno(const std::string& path, const char* what, int err) {
  throw std::runtime_error("CSV output '" + path + "': " + what + ": " + std::strerror(err));
}

}  // namespace

CsvWriter::CsvWriter(const std::string& path, std::vector<std::string> columns)
    : path_(path), columns_(std::move(columns)) {
  PERIDOT_REQUIRE(!columns_.empty(), "a CSV file needs at least one column");
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) throw_errno(path_, "cannot create", errno);
  for (std::size_t k = 0; k < columns_.size(); ++k) {
    if (k) line_ += ',';
    line_ += quoted(columns_[k]);
  }
  line_ += '\n';
  header_ = line_;
  try {
    write_line();
  } catch (...) {
    ::close(fd_);
    fd_ = -1;
    throw;
  }
}

CsvWriter::CsvWriter(CsvWriter&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)),
      path_(std::move(other.path_)),
      columns_(std::move(other.columns_)),
      header_(std::move(other.header_)),
      line_(std::move(other.line_)) {}

CsvWriter& CsvWriter::operator=(CsvWriter&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = std::exchange(other.fd_, -1);
    path_ = std::move(other.path_);
    columns_ = std::move(other.columns_);
    header_ = std::move(other.header_);
    line_ = std::move(other.line_);
  }
  return *this;
}

CsvWriter::~CsvWriter() {
  if (fd_ >= 0) ::close(fd_);
}

void CsvWriter::close() {
  if (fd_ < 0) return;
  const int fd = std::exchange(fd_, -1);
  if (::close(fd) != 0) throw_errno(path_, "close", errno);
}

void CsvWriter::write_row(const std::vector<double>& values) {
  PERIDOT_REQUIRE(fd_ >= 0, "write_row on a closed CSV writer");
  PERIDOT_REQUIRE(values.size() == columns_.size(),
                  "CSV row has " + std::to_string(values.size()) + " values for " +
                      std::to_string(columns_.size()) + " columns");
  line_.clear();
  char number[32];  // %.17g of a double needs at most 24 characters
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (k) line_ += ',';
    const int len = std::snprintf(number, sizeof number, "%.17g", values[k]);
    line_.append(number, static_cast<std::size_t>(len));
  }
  line_ += '\n';
  write_line();
}

void CsvWriter::write_line() {
  // One write(2) normally takes the whole line; the loop only matters after a signal or a full disk.
  const char* p = line_.data();
  std::size_t left = line_.size();
  while (left > 0) {
    const ssize_t written = ::write(fd_, p, left);
    if (written < 0) {
      if (errno == EINTR) continue;
      throw_errno(path_, "write", errno);
    }
    p += written;
    left -= static_cast<std::size_t>(written);
  }
}

std::int64_t CsvWriter::copy_rows(const std::string& earlier, std::int64_t last_step, std::int64_t every) {
  PERIDOT_REQUIRE(fd_ >= 0, "copy_rows on a closed CSV writer");
  std::ifstream in(earlier, std::ios::binary);
  if (!in) throw_errno(earlier, "cannot read", errno);
  std::stringstream text;
  text << in.rdbuf();
  const std::string all = text.str();
  if (all.compare(0, header_.size(), header_) != 0)
    throw std::runtime_error("CSV history '" + earlier + "' has other columns than this run writes");
  std::int64_t copied = 0;
  for (std::size_t at = header_.size(); at < all.size();) {
    const std::size_t end = all.find('\n', at);
    if (end == std::string::npos) break;  // a line cut short by a kill
    const std::size_t comma = all.find(',', at);
    if (comma < end) {
      const auto step = static_cast<std::int64_t>(std::strtod(all.c_str() + comma + 1, nullptr));
      if (step <= last_step && step % every == 0) {
        line_.assign(all, at, end + 1 - at);
        write_line();
        ++copied;
      }
    }
    at = end + 1;
  }
  return copied;
}

}  // namespace peridot
