#pragma once
// Scalar functions of position and time written in the deck ("100*(y-0.025)", "-20*min(t/1e-6,1)"),
// evaluated by muParser. Variables x, y, z (m) and t (s), the constant pi and muParser's functions
// (sin, exp, sqrt, min, max, abs, the ternary a ? b : c, ...).
#include <memory>
#include <string>

#include "peridot/deck/problem.hpp"

namespace peridot {

namespace detail {
struct CompiledExpression;  // muParser and the variables it points to
}

/// The outcome of checking an expression's text without evaluating it at any particular point.
struct ExpressionCheck {
  bool ok = false;
  std::string message;  ///< muParser's message when not ok
  int position = 0;     ///< 0-based character of the problem in the text
  bool uses_time = false;
};
ExpressionCheck check_expression(const std::string& text);

/// An expression compiled once, evaluated many times. Not thread-safe (muParser keeps state):
/// give each thread its own copy.
class ScalarFunction {
 public:
  explicit ScalarFunction(const Expression& e);  ///< throws InputError at e.pos when malformed
  ScalarFunction(const ScalarFunction& other);
  ScalarFunction& operator=(const ScalarFunction& other);
  ScalarFunction(ScalarFunction&&) noexcept;
  ScalarFunction& operator=(ScalarFunction&&) noexcept;
  ~ScalarFunction();

  double operator()(double x, double y, double z, double t) const;
  /// The value at t = 0, for setting up a run: throws InputError at the expression when it is not finite
  /// there (a deck whose loads start as inf or NaN is refused by `check`, not found in the first step).
  double at_start(double x, double y, double z) const;
  bool depends_on_time() const { return expression_.depends_on_time; }
  const Expression& expression() const { return expression_; }

 private:
  Expression expression_;
  // The parser holds pointers to its variables, so both live on the heap and move together.
  std::unique_ptr<detail::CompiledExpression> compiled_;
};

}  // namespace peridot
