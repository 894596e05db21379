#pragma once
// Two kinds of failure, each with its own exit status (docs/design.md "Bad input and failures"):
//  - InputError: a deck or input-file problem the user can fix; exit status 2, nothing written.
//  - NumericalError: the run itself failed (NaN, blow-up); exit status 3, outputs closed and readable.
// PERIDOT_REQUIRE is always on (invariants a user can break); PERIDOT_ASSERT is debug-only.
#include <stdexcept>
#include <string>
#include <vector>

namespace peridot {

/// A position in an input file, 1-based line and column (0 = unknown).
struct SourcePos {
  std::string file;
  int line = 0;
  int column = 0;
  std::string str() const;  ///< "file:line:col" (or just "file" when the line is unknown)
};

struct Diagnostic {
  SourcePos pos;
  std::string message;  ///< already prefixed by the deck path it concerns, e.g. "materials.steel: ..."
  bool is_warning = false;
  std::string str() const;  ///< "deck.yaml:14:7: error: materials.steel: unknown key ..."
};

/// Every problem found in an input, reported together.
class InputError : public std::runtime_error {
 public:
  explicit InputError(std::vector<Diagnostic> diagnostics);
  InputError(SourcePos pos, const std::string& message);
  const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }

 private:
  std::vector<Diagnostic> diagnostics_;
};

/// A failure of the numerical solution (names step, time, point and position in its message).
class NumericalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A failure to write an output (disk full, no permission) during a run. Distributed, every rank throws it
/// with rank 0's message, so that every rank stops and one reports it.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// An internal invariant that a user can break through the API (always checked).
[[noreturn]] void fail_invariant(const char* expr, const char* file, int line, const std::string& message);

}  // namespace peridot

#define PERIDOT_REQUIRE(cond, msg) \
  do { if (!(cond)) ::peridot::fail_invariant(#cond, __FILE__, __LINE__, (msg)); } while (0)
#ifndef NDEBUG
#define PERIDOT_ASSERT(cond) PERIDOT_REQUIRE(cond, "internal assertion")
#else
#define PERIDOT_ASSERT(cond) ((void)0)
#endif
