#include "peridot/deck/expression.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <muParser.h>

namespace peridot {

namespace detail {
struct CompiledExpression {
  double x = 0, y = 0, z = 0, t = 0;
  mu::Parser parser;

  explicit CompiledExpression(const std::string& text) {
    parser.DefineVar("x", &x);
    parser.DefineVar("y", &y);
    parser.DefineVar("z", &z);
    parser.DefineVar("t", &t);
    parser.DefineConst("pi", std::numbers::pi);
    parser.SetExpr(text);
  }
};
}  // namespace detail

ExpressionCheck check_expression(const std::string& text) {
  ExpressionCheck check;
  try {
    detail::CompiledExpression compiled(text);
    // GetUsedVar parses the whole expression (syntax, unknown names) without evaluating it.
    const mu::varmap_type& used = compiled.parser.GetUsedVar();
    check.uses_time = used.count("t") > 0;
    compiled.parser.Eval();  // catches what only evaluation reveals (e.g. wrong argument counts)
    check.ok = true;
  } catch (const mu::Parser::exception_type& e) {
    check.message = e.GetMsg();
    // muParser may point one past the end ("unexpected end of expression"); keep it on the text's end.
    check.position = std::clamp(static_cast<int>(e.GetPos()), 0, static_cast<int>(text.size()));
  }
  return check;
}

ScalarFunction::ScalarFunction(const Expression& e) : expression_(e) {
  ExpressionCheck check = check_expression(e.text);
  if (!check.ok) {
    SourcePos at = e.pos;
    if (at.line > 0) at.column += check.position;
    throw InputError(at, "malformed expression '" + e.text + "': " + check.message);
  }
  expression_.depends_on_time = check.uses_time;
  compiled_ = std::make_unique<detail::CompiledExpression>(e.text);
}

ScalarFunction::ScalarFunction(const ScalarFunction& other)
    : expression_(other.expression_), compiled_(std::make_unique<detail::CompiledExpression>(other.expression_.text)) {}

ScalarFunction& ScalarFunction::operator=(const ScalarFunction& other) {
  if (this != &other) *this = ScalarFunction(other);
  return *this;
}

ScalarFunction::ScalarFunction(ScalarFunction&&) noexcept = default;
ScalarFunction& ScalarFunction::operator=(ScalarFunction&&) noexcept = default;
ScalarFunction::~ScalarFunction() = default;

double ScalarFunction::operator()(double x, double y, double z, double t) const {
  detail::CompiledExpression& c = *compiled_;
  c.x = x, c.y = y, c.z = z, c.t = t;
  return c.parser.Eval();
}

double ScalarFunction::at_start(double x, double y, double z) const {
  const double value = (*this)(x, y, z, 0.0);
  if (!std::isfinite(value))
    throw InputError(expression_.pos, fmt::format("expression '{}' is {} at t = 0 at ({:g}, {:g}, {:g}) m",
                                                  expression_.text, value, x, y, z));
  return value;
}

}  // namespace peridot
