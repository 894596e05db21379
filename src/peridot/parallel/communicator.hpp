#pragma once
// The ranks of a run. A run started by an MPI launcher (mpirun, srun) is distributed over
// MPI_COMM_WORLD; a run started directly is one rank and calls no MPI function at all, so the serial
// program needs neither a launcher nor an MPI daemon. Every collective here is deterministic: min, max,
// logical or and integer sums do not depend on the order in which ranks contribute. Floating-point sums
// are reduced across ranks only as exact sums (sum(std::vector<ExactSum>&): integers) or as the fixed-point
// reproducible_sum below, so a printed total is the same bits for any number of ranks.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <mpi.h>

#include "peridot/core/exact_sum.hpp"

namespace peridot {

class Communicator {
 public:
  /// One rank, no MPI.
  Communicator() = default;
  /// MPI_COMM_WORLD when MpiSession initialised MPI, else the serial communicator.
  static Communicator world();

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool serial() const { return size_ == 1; }
  bool is_root() const { return rank_ == 0; }
  MPI_Comm mpi() const { return comm_; }

  double min(double x) const;
  double max(double x) const;
  std::uint64_t sum(std::uint64_t x) const;
  std::int64_t sum(std::int64_t x) const;
  bool any(bool x) const;
  /// Every rank's exact sums added together, in place: the same bits for any rank count (core/exact_sum.hpp).
  void sum(std::vector<ExactSum>& sums) const;
  /// The lowest rank for which x is true, or −1 when none.
  int first_rank_with(bool x) const;
  /// Rank `from`'s text, on every rank.
  std::string broadcast(const std::string& text, int from) const;
  void barrier() const;

  /// Personalised exchange: `values` holds count[r] values for each rank r, rank after rank; returns what
  /// every rank sent to this one, source after source, and its counts per source in `received`.
  template <class T>
  std::vector<T> all_to_all(const std::vector<T>& values, const std::vector<int>& count, std::vector<int>& received) const;
  /// Offsets of consecutive groups of the given sizes (exclusive prefix sum).
  static std::vector<int> offsets(const std::vector<int>& count);

  /// Concatenation of every rank's values in rank order, on rank 0 (other ranks get an empty vector).
  template <class T>
  std::vector<T> gather(const std::vector<T>& local) const;
  /// Concatenation of every rank's values in rank order, on every rank.
  template <class T>
  std::vector<T> all_gather(const std::vector<T>& local) const;

 private:
  MPI_Comm comm_ = MPI_COMM_NULL;
  int rank_ = 0, size_ = 1;
};

/// Initialises MPI for the lifetime of the object when the process was started by an MPI launcher
/// (Open MPI's OMPI_COMM_WORLD_SIZE, PMI/PMIx, Slurm's PMI variables) or PERIDOT_MPI=1 is set;
/// otherwise does nothing. A run with one rank under mpirun takes the same serial code path.
class MpiSession {
 public:
  MpiSession(int& argc, char**& argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  static bool active();
  /// Ends every rank at once (a rank that cannot reach the others' next collective).
  [[noreturn]] static void abort(int status);
};

template <class T>
MPI_Datatype mpi_type();
template <> inline MPI_Datatype mpi_type<double>() { return MPI_DOUBLE; }
template <> inline MPI_Datatype mpi_type<std::uint32_t>() { return MPI_UINT32_T; }
template <> inline MPI_Datatype mpi_type<std::int32_t>() { return MPI_INT32_T; }
template <> inline MPI_Datatype mpi_type<unsigned char>() { return MPI_UNSIGNED_CHAR; }
template <> inline MPI_Datatype mpi_type<std::uint64_t>() { return MPI_UINT64_T; }

template <class T>
std::vector<T> Communicator::all_to_all(const std::vector<T>& values, const std::vector<int>& count,
                                        std::vector<int>& received) const {
  if (serial()) {
    received = count;
    return values;
  }
  received.assign(static_cast<std::size_t>(size_), 0);
  MPI_Alltoall(count.data(), 1, MPI_INT, received.data(), 1, MPI_INT, comm_);
  const std::vector<int> send_displ = offsets(count), receive_displ = offsets(received);
  std::vector<T> out(static_cast<std::size_t>(receive_displ.back() + received.back()));
  MPI_Alltoallv(values.data(), count.data(), send_displ.data(), mpi_type<T>(), out.data(), received.data(),
                receive_displ.data(), mpi_type<T>(), comm_);
  return out;
}

template <class T>
std::vector<T> Communicator::gather(const std::vector<T>& local) const {
  if (serial()) return local;
  const int count = static_cast<int>(local.size());
  std::vector<int> counts(is_root() ? size_ : 0), displs;
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm_);
  std::vector<T> out;
  if (is_root()) {
    displs.assign(size_, 0);
    for (int r = 1; r < size_; ++r) displs[r] = displs[r - 1] + counts[r - 1];
    out.resize(static_cast<std::size_t>(displs.back() + counts.back()));
  }
  MPI_Gatherv(local.data(), count, mpi_type<T>(), out.data(), counts.data(), displs.data(), mpi_type<T>(), 0, comm_);
  return out;
}

template <class T>
std::vector<T> Communicator::all_gather(const std::vector<T>& local) const {
  if (serial()) return local;
  const int count = static_cast<int>(local.size());
  std::vector<int> counts(size_), displs(size_, 0);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, comm_);
  for (int r = 1; r < size_; ++r) displs[r] = displs[r - 1] + counts[r - 1];
  std::vector<T> out(static_cast<std::size_t>(displs.back() + counts.back()));
  MPI_Allgatherv(local.data(), count, mpi_type<T>(), out.data(), counts.data(), displs.data(), mpi_type<T>(), comm_);
  return out;
}

/// Σ_{i<n} term(i) over every rank's terms with the same bits for any number of ranks and threads, where a
/// floating-point reduction depends on how the terms are split: each term is rounded to a multiple of 2^e,
/// e chosen from the largest |term| of all ranks and the total count so that the integer sum cannot
/// overflow, and the integers are added exactly. The result is within N 2^(e−1) ≤ 4e-19 N² max|term| of
/// the exact sum (N terms in all): meant for decisions such as a sign, not for reported totals. Collective.
template <class Term>
double reproducible_sum(const Communicator& comm, std::size_t n, Term&& term) {
  double largest = 0;
#pragma omp parallel for schedule(static) reduction(max : largest)
  for (std::size_t i = 0; i < n; ++i) largest = std::max(largest, std::abs(term(i)));
  largest = comm.max(largest);
  const std::uint64_t total = comm.sum(static_cast<std::uint64_t>(n));
  if (!(largest > 0) || total == 0) return 0.0;
  int exponent = 0;
  std::frexp(largest, &exponent);  // largest < 2^exponent
  int count_bits = 0;
  while (count_bits < 63 && (std::uint64_t{1} << count_bits) < total) ++count_bits;
  const int e = exponent - 62 + count_bits;  // total · 2^(exponent − e) ≤ 2^62
  std::int64_t local = 0;
#pragma omp parallel for schedule(static) reduction(+ : local)
  for (std::size_t i = 0; i < n; ++i) local += std::llround(std::ldexp(term(i), -e));
  return std::ldexp(static_cast<double>(comm.sum(local)), e);
}

}  // namespace peridot
