#include "peridot/parallel/communicator.hpp"

#include <algorithm>
#include <cstdlib>

namespace peridot {

namespace {

bool started_by_launcher() {
  if (const char* forced = std::getenv("PERIDOT_MPI")) return std::string(forced) == "1";
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(name)) return true;
  return false;
}

bool session_active = false;

}  // namespace

MpiSession::MpiSession(int& argc, char**& argv) {
  if (!started_by_launcher()) return;
  int provided = 0;
  // Threads: OpenMP runs inside a rank; only the main thread calls MPI.
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  session_active = true;
}

MpiSession::~MpiSession() {
  if (session_active) MPI_Finalize();
  session_active = false;
}

bool MpiSession::active() { return session_active; }

void MpiSession::abort(int status) {
  if (session_active) MPI_Abort(MPI_COMM_WORLD, status);
  std::exit(status);
}

Communicator Communicator::world() {
  Communicator c;
  if (!MpiSession::active()) return c;
  c.comm_ = MPI_COMM_WORLD;
  MPI_Comm_rank(c.comm_, &c.rank_);
  MPI_Comm_size(c.comm_, &c.size_);
  return c;
}

double Communicator::min(double x) const {
  if (serial()) return x;
  double out = x;
  MPI_Allreduce(&x, &out, 1, MPI_DOUBLE, MPI_MIN, comm_);
  return out;
}

double Communicator::max(double x) const {
  if (serial()) return x;
  double out = x;
  MPI_Allreduce(&x, &out, 1, MPI_DOUBLE, MPI_MAX, comm_);
  return out;
}

std::uint64_t Communicator::sum(std::uint64_t x) const {
  if (serial()) return x;
  std::uint64_t out = x;
  MPI_Allreduce(&x, &out, 1, MPI_UINT64_T, MPI_SUM, comm_);
  return out;
}

std::int64_t Communicator::sum(std::int64_t x) const {
  if (serial()) return x;
  std::int64_t out = x;
  MPI_Allreduce(&x, &out, 1, MPI_INT64_T, MPI_SUM, comm_);
  return out;
}

bool Communicator::any(bool x) const {
  if (serial()) return x;
  int in = x ? 1 : 0, out = 0;
  MPI_Allreduce(&in, &out, 1, MPI_INT, MPI_LOR, comm_);
  return out != 0;
}

int Communicator::first_rank_with(bool x) const {
  if (serial()) return x ? 0 : -1;
  int in = x ? rank_ : size_, out = size_;
  MPI_Allreduce(&in, &out, 1, MPI_INT, MPI_MIN, comm_);
  return out == size_ ? -1 : out;
}

std::string Communicator::broadcast(const std::string& text, int from) const {
  if (serial()) return text;
  std::uint64_t length = text.size();
  MPI_Bcast(&length, 1, MPI_UINT64_T, from, comm_);
  std::string out = rank_ == from ? text : std::string(length, '\0');
  MPI_Bcast(out.data(), static_cast<int>(length), MPI_CHAR, from, comm_);
  return out;
}

std::vector<int> Communicator::offsets(const std::vector<int>& count) {
  std::vector<int> displ(count.size(), 0);
  for (std::size_t r = 1; r < count.size(); ++r) displ[r] = displ[r - 1] + count[r - 1];
  return displ;
}

void Communicator::sum(std::vector<ExactSum>& sums) const {
  if (serial()) return;
  constexpr std::size_t width = ExactSum::digits + 3;  // the digits, then how many ranks had each Special flag
  std::vector<std::int64_t> digits;
  for (const ExactSum& s : sums) {
    const ExactSum::Digits d = s.canonical();
    digits.insert(digits.end(), d.begin(), d.end());
    for (std::uint8_t flag : {ExactSum::plus_infinity, ExactSum::minus_infinity, ExactSum::not_a_number})
      digits.push_back((s.special() & flag) ? 1 : 0);
  }
  MPI_Allreduce(MPI_IN_PLACE, digits.data(), static_cast<int>(digits.size()), MPI_INT64_T, MPI_SUM, comm_);
  for (std::size_t k = 0; k < sums.size(); ++k) {
    ExactSum::Digits d;
    const auto first = digits.begin() + static_cast<std::ptrdiff_t>(k * width);
    std::copy(first, first + ExactSum::digits, d.begin());
    std::uint8_t special = 0;
    for (int f = 0; f < 3; ++f)
      if (first[ExactSum::digits + f] > 0) special |= static_cast<std::uint8_t>(1 << f);
    sums[k].load(d, special);
  }
}

void Communicator::barrier() const {
  if (!serial()) MPI_Barrier(comm_);
}

}  // namespace peridot
