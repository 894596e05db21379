#pragma once
// The exact sum of any number of doubles, rounded once at the end: the same bits whatever the order of the
// terms and however they are split among threads and ranks (an integer accumulator over the whole exponent
// range of a double, in 32-bit digits held in 64-bit words). A reported total summed this way is also the
// correctly rounded sum, not one order's rounding of it.
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

namespace peridot {

class ExactSum {
 public:
  /// Digits of 32 bits from 2^-1074 (the smallest subnormal) up, with room for 2^62 terms' carries.
  static constexpr int digits = 70;
  using Digits = std::array<std::int64_t, digits>;

  ExactSum() { digits_.fill(0); }

  /// Non-finite terms, as flags: the sum is +∞ with only +∞ among them, −∞ with only −∞, else NaN.
  enum Special : std::uint8_t { plus_infinity = 1, minus_infinity = 2, not_a_number = 4 };

  /// Adds x exactly (a non-finite x is remembered as such).
  void add(double x) {
    if (x == 0) return;
    if (!std::isfinite(x)) {
      special_ |= std::isnan(x) ? not_a_number : x > 0 ? plus_infinity : minus_infinity;
      return;
    }
    int exponent = 0;
    const double fraction = std::frexp(x, &exponent);  // x = fraction · 2^exponent, 0.5 ≤ |fraction| < 1
    // x = m · 2^(exponent − 53), m an integer of at most 53 bits; bit position above 2^-1074:
    std::int64_t m = static_cast<std::int64_t>(std::ldexp(fraction, 53));
    int position = exponent - 53 + 1074;
    if (position < 0) {  // subnormal: m has low zero bits to drop
      m >>= -position;   // exact: those bits are zero for a representable x
      position = 0;
    }
    const bool negative = m < 0;
    std::uint64_t magnitude = static_cast<std::uint64_t>(negative ? -m : m);
    int digit = position / 32;
    const int shift = position % 32;
    // magnitude · 2^shift spans at most 85 bits: three digits.
    const unsigned __int128 shifted = static_cast<unsigned __int128>(magnitude) << shift;
    for (int k = 0; k < 3 && digit + k < digits; ++k) {
      const auto chunk = static_cast<std::int64_t>(static_cast<std::uint64_t>(shifted >> (32 * k)) & 0xffffffffu);
      digits_[digit + k] += negative ? -chunk : chunk;
    }
    if (++pending_ == (std::int64_t{1} << 30)) normalize();  // every digit stays far from overflow
  }

  /// Adds another accumulator (another thread's or rank's part).
  void add(const ExactSum& other) {
    normalize();
    Digits theirs = other.digits_;
    carry(theirs);
    for (int k = 0; k < digits; ++k) digits_[k] += theirs[k];
    special_ |= other.special_;
    normalize();
  }

  /// The digits in canonical form (each in [0, 2^32) but the last, which carries the sign): what ranks add
  /// together (an integer all-reduce), then load.
  Digits canonical() const {
    Digits d = digits_;
    carry(d);
    return d;
  }
  /// Replaces the sum by the given digits (a sum of canonical() of every part) and non-finite flags (Special).
  void load(const Digits& d, std::uint8_t special) {
    digits_ = d;
    special_ = special;
    normalize();
  }
  std::uint8_t special() const { return special_; }

  /// The sum rounded to the nearest double (ties to even).
  double value() const {
    if (special_ == plus_infinity) return std::numeric_limits<double>::infinity();
    if (special_ == minus_infinity) return -std::numeric_limits<double>::infinity();
    if (special_ != 0) return std::numeric_limits<double>::quiet_NaN();
    Digits d = canonical();
    const bool negative = d[digits - 1] < 0;
    if (negative) {  // two's complement of the whole number, digit by digit
      std::int64_t borrow = 0;
      for (int k = 0; k < digits; ++k) {
        std::int64_t v = -d[k] - borrow;
        borrow = 0;
        if (v < 0 && k < digits - 1) {
          v += std::int64_t{1} << 32;
          borrow = 1;
        }
        d[k] = v;
      }
    }
    int top = digits - 1;
    while (top >= 0 && d[top] == 0) --top;
    if (top < 0) return 0.0;
    // The highest 64 bits, and whether anything below them is non-zero (a sticky bit in the lowest place
    // makes the conversion to double round as the exact number would).
    unsigned __int128 high = 0;
    int low_digit = top;
    for (int k = top; k >= 0 && k > top - 3; --k, --low_digit) high = (high << 32) | static_cast<std::uint64_t>(d[k]);
    bool sticky = false;
    for (int k = low_digit; k >= 0; --k) sticky = sticky || d[k] != 0;
    // high holds the digits low_digit + 1 … top: up to 96 bits; keep the top 64 of them.
    int bits = 0;
    for (unsigned __int128 h = high; h != 0; h >>= 1) ++bits;
    const int drop = bits > 64 ? bits - 64 : 0;
    if (drop > 0) {
      sticky = sticky || (high & ((static_cast<unsigned __int128>(1) << drop) - 1)) != 0;
      high >>= drop;
    }
    std::uint64_t top64 = static_cast<std::uint64_t>(high);
    if (sticky) top64 |= 1;
    // Valid while the leading bit is at least 11 places above the sticky: 64 bits kept, 53 significant.
    const double magnitude = std::ldexp(static_cast<double>(top64), 32 * (low_digit + 1) + drop - 1074);
    return negative ? -magnitude : magnitude;
  }

 private:
  static void carry(Digits& d) {
    for (int k = 0; k < digits - 1; ++k) {
      const std::int64_t c = d[k] >> 32;  // floor division by 2^32 (arithmetic shift)
      d[k] -= c * (std::int64_t{1} << 32);
      d[k + 1] += c;
    }
  }
  void normalize() {
    carry(digits_);
    pending_ = 0;
  }

  Digits digits_;
  std::int64_t pending_ = 0;
  std::uint8_t special_ = 0;
};

}  // namespace peridot
