#include "peridot/core/error.hpp"

#include <sstream>

namespace peridot {

std::string SourcePos::str() const {
  if (line <= 0) return file;
  return file + ":" + std::to_string(line) + ":" + std::to_string(column);
}

std::string Diagnostic::str() const {
  std::string where = pos.str();
  return (where.empty() ? std::string() : where + ": ") + (is_warning ? "warning: " : "error: ") + message;
}

static std::string join(const std::vector<Diagnostic>& diagnostics) {
  std::ostringstream out;
  for (std::size_t k = 0; k < diagnostics.size(); ++k) out << (k ? "\n" : "") << diagnostics[k].str();
  return out.str();
}

InputError::InputError(std::vector<Diagnostic> diagnostics)
    : std::runtime_error(join(diagnostics)), diagnostics_(std::move(diagnostics)) {}

InputError::InputError(SourcePos pos, const std::string& message)
    : InputError(std::vector<Diagnostic>{Diagnostic{std::move(pos), message, false}}) {}

void fail_invariant(const char* expr, const char* file, int line, const std::string& message) {
  throw std::logic_error(std::string(file) + ":" + std::to_string(line) + ": invariant '" + expr +
                         "' violated: " + message);
}

}  // namespace peridot
