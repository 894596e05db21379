#pragma once
// History output as CSV: a header line, then one line per row, every number with 17 significant digits
// (%.17g, enough to read the same double back). Each line goes to the file in a single write(2) of the whole
// line, straight to the kernel with no user-space buffer, so a killed run leaves only whole lines (the
// kernel does not split a write to a regular file unless the disk is full or the process is stopped inside
// that very call, which a kill between rows cannot do).
#include <cstdint>
#include <string>
#include <vector>

namespace peridot {

class CsvWriter {
 public:
  /// Creates (truncates) the file and writes the header. Column names containing a comma, a quote or a line
  /// break are quoted as RFC 4180 says. Throws std::runtime_error naming the path and errno's text.
  CsvWriter(const std::string& path, std::vector<std::string> columns);
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;
  CsvWriter(CsvWriter&& other) noexcept;
  CsvWriter& operator=(CsvWriter&& other) noexcept;
  ~CsvWriter();

  /// One value per column (std::logic_error otherwise); throws std::runtime_error if the write fails.
  void write_row(const std::vector<double>& values);
  /// A restart's continuation (solvers/runner.hpp): appends the rows of the earlier file `earlier` whose
  /// second column (the step) is at most last_step and a multiple of every, byte for byte (a row a stopped run
  /// wrote off its schedule is not kept; a last line without its line break is not a row). Returns how many.
  /// Throws std::runtime_error when that file cannot be read or has another header.
  std::int64_t copy_rows(const std::string& earlier, std::int64_t last_step, std::int64_t every);
  void close();  ///< idempotent; the destructor closes too

  const std::vector<std::string>& columns() const { return columns_; }
  const std::string& path() const { return path_; }

 private:
  void write_line();  // writes line_ whole

  int fd_ = -1;
  std::string path_;
  std::vector<std::string> columns_;
  std::string header_;  // the header line as written
  std::string line_;    // reused for every row
};

}  // namespace peridot
