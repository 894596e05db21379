#pragma once
// A sum over points whose bits do not depend on the number of threads.
#include <algorithm>
#include <cstddef>
#include <vector>

namespace peridot {

/// Sum of term(i) over i < n in chunks of fixed size, chunk results added in order: bitwise the same for
/// any number of threads.
template <class Term>
double deterministic_sum(std::size_t n, Term&& term) {
  constexpr std::size_t chunk = 4096;
  const std::size_t chunks = (n + chunk - 1) / chunk;
  std::vector<double> partial(chunks, 0.0);
#pragma omp parallel for schedule(static)
  for (std::size_t c = 0; c < chunks; ++c) {
    double sum = 0;
    const std::size_t end = std::min(n, (c + 1) * chunk);
    for (std::size_t i = c * chunk; i < end; ++i) sum += term(i);
    partial[c] = sum;
  }
  double total = 0;
  for (double p : partial) total += p;
  return total;
}

}  // namespace peridot
