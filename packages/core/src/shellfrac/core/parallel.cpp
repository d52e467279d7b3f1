#include "shellfrac/core/parallel.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <exception>

#include "shellfrac/core/error.hpp"

namespace shellfrac::parallel {

int rank(MPI_Comm comm) {
  int r = 0;
  MPI_Comm_rank(comm, &r);
  return r;
}

int size(MPI_Comm comm) {
  int s = 1;
  MPI_Comm_size(comm, &s);
  return s;
}

const char* ByteReader::take(std::size_t n) {
  SHELLFRAC_REQUIRE(pos_ + n <= buf_.size(), "ByteReader: read past the end of the buffer");
  const char* p = buf_.data() + pos_;
  pos_ += n;
  return p;
}

void broadcast(std::vector<char>& buf, int root, MPI_Comm comm) {
  std::uint64_t n = buf.size();
  MPI_Bcast(&n, 1, MPI_UINT64_T, root, comm);
  if (rank(comm) != root) buf.resize(n);
  // MPI counts are int: send in chunks so meshes larger than 2 GiB still broadcast.
  constexpr std::uint64_t chunk = 1u << 30;
  for (std::uint64_t off = 0; off < n; off += chunk) {
    const int len = static_cast<int>(std::min<std::uint64_t>(chunk, n - off));
    MPI_Bcast(buf.data() + off, len, MPI_CHAR, root, comm);
  }
}

void broadcast(std::string& s, int root, MPI_Comm comm) {
  std::vector<char> buf(s.begin(), s.end());
  broadcast(buf, root, comm);
  s.assign(buf.begin(), buf.end());
}

namespace {
// kind: 0 = ok, 1 = InputError, 2 = other error
int run_capturing(const std::function<void()>& fn, std::string& msg) {
  try {
    fn();
    return 0;
  } catch (const InputError& e) {
    msg = e.what();
    return 1;
  } catch (const OutputError& e) {
    msg = e.what();
    return 3;
  } catch (const std::exception& e) {
    msg = e.what();
    return 2;
  }
}

[[noreturn]] void rethrow(int kind, const std::string& msg) {
  if (kind == 1) throw InputError(msg);
  if (kind == 3) throw OutputError(msg);
  throw Error(msg);
}
}  // namespace

void on_root_then_agree(const std::function<void()>& fn, int root, MPI_Comm comm) {
  std::string msg;
  int kind = 0;
  if (rank(comm) == root) kind = run_capturing(fn, msg);
  MPI_Bcast(&kind, 1, MPI_INT, root, comm);
  if (kind == 0) return;
  broadcast(msg, root, comm);
  rethrow(kind, msg);
}

void on_all_then_agree(const std::function<void()>& fn, MPI_Comm comm) {
  std::string msg;
  const int kind = run_capturing(fn, msg);
  const int me = rank(comm);
  int failing = kind != 0 ? me : size(comm);
  int first = 0;
  MPI_Allreduce(&failing, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == size(comm)) return;
  int k = kind;
  MPI_Bcast(&k, 1, MPI_INT, first, comm);
  broadcast(msg, first, comm);
  if (size(comm) > 1) msg = "rank " + std::to_string(first) + ": " + msg;
  rethrow(k, msg);
}

bool any(bool local, MPI_Comm comm) {
  int l = local ? 1 : 0, g = 0;
  MPI_Allreduce(&l, &g, 1, MPI_INT, MPI_LOR, comm);
  return g != 0;
}

std::int64_t sum(std::int64_t local, MPI_Comm comm) {
  std::int64_t g = 0;
  MPI_Allreduce(&local, &g, 1, MPI_INT64_T, MPI_SUM, comm);
  return g;
}

double max(double local, MPI_Comm comm) {
  double g = 0;
  MPI_Allreduce(&local, &g, 1, MPI_DOUBLE, MPI_MAX, comm);
  return g;
}

std::vector<double> all_to_all(const std::vector<std::vector<double>>& send, MPI_Comm comm) {
  const int P = size(comm);
  SHELLFRAC_REQUIRE(int(send.size()) == P, "all_to_all: " << send.size() << " send vectors for " << P << " ranks");
  std::vector<int> send_count(static_cast<std::size_t>(P)), receive_count(static_cast<std::size_t>(P));
  std::vector<int> send_offset(static_cast<std::size_t>(P) + 1, 0), receive_offset(static_cast<std::size_t>(P) + 1, 0);
  for (int q = 0; q < P; ++q) send_count[std::size_t(q)] = static_cast<int>(send[std::size_t(q)].size());
  MPI_Alltoall(send_count.data(), 1, MPI_INT, receive_count.data(), 1, MPI_INT, comm);
  for (std::size_t q = 0; q < std::size_t(P); ++q)
    send_offset[q + 1] = send_offset[q] + send_count[q], receive_offset[q + 1] = receive_offset[q] + receive_count[q];
  std::vector<double> outgoing(static_cast<std::size_t>(send_offset[std::size_t(P)]));
  std::vector<double> incoming(static_cast<std::size_t>(receive_offset[std::size_t(P)]));
  for (std::size_t q = 0; q < std::size_t(P); ++q)
    std::copy(send[q].begin(), send[q].end(), outgoing.begin() + send_offset[q]);
  MPI_Alltoallv(outgoing.data(), send_count.data(), send_offset.data(), MPI_DOUBLE, incoming.data(),
                receive_count.data(), receive_offset.data(), MPI_DOUBLE, comm);
  return incoming;
}

void exchange_bytes(const char* out, const std::vector<std::size_t>& send_bytes,
                    const std::function<char*(std::size_t)>& allocate, std::vector<std::size_t>& received_bytes,
                    MPI_Comm comm) {
  const int P = size(comm);
  SHELLFRAC_REQUIRE(int(send_bytes.size()) == P,
                    "exchange: " << send_bytes.size() << " send vectors for " << P << " ranks");
  constexpr std::size_t limit = 2147483647u;
  std::vector<int> send_count(static_cast<std::size_t>(P)), receive_count(static_cast<std::size_t>(P));
  std::vector<int> send_offset(static_cast<std::size_t>(P), 0), receive_offset(static_cast<std::size_t>(P), 0);
  std::size_t sent = 0;
  for (std::size_t q = 0; q < std::size_t(P); ++q) {
    send_offset[q] = static_cast<int>(sent);
    send_count[q] = static_cast<int>(send_bytes[q]);
    sent += send_bytes[q];
  }
  const bool too_many_sent = sent > limit;
  MPI_Alltoall(send_count.data(), 1, MPI_INT, receive_count.data(), 1, MPI_INT, comm);
  std::size_t received = 0;
  for (std::size_t q = 0; q < std::size_t(P); ++q) {
    receive_offset[q] = static_cast<int>(std::min(received, limit));
    received += std::size_t(receive_count[q]);
  }
  SHELLFRAC_REQUIRE(!any(too_many_sent || received > limit, comm),
                    "exchange: more than 2^31 - 1 bytes to or from one rank in one exchange");
  char* in = allocate(received);
  char dummy_out = 0, dummy_in = 0;
  SHELLFRAC_REQUIRE(MPI_Alltoallv(sent > 0 ? out : &dummy_out, send_count.data(), send_offset.data(), MPI_BYTE,
                                  received > 0 ? in : &dummy_in, receive_count.data(), receive_offset.data(), MPI_BYTE,
                                  comm) == MPI_SUCCESS,
                    "exchange: MPI_Alltoallv failed");
  received_bytes.assign(std::size_t(P), 0);
  for (std::size_t q = 0; q < std::size_t(P); ++q) received_bytes[q] = std::size_t(receive_count[q]);
}

template <class T>
std::vector<T> all_gather(const std::vector<T>& local, MPI_Comm comm) {
  static_assert(std::is_trivially_copyable_v<T>);
  const int np = size(comm);
  int my_bytes = static_cast<int>(local.size() * sizeof(T));
  std::vector<int> counts(np), displs(np, 0);
  MPI_Allgather(&my_bytes, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  for (int r = 1; r < np; ++r) displs[r] = displs[r - 1] + counts[r - 1];
  std::vector<T> out((displs[np - 1] + counts[np - 1]) / sizeof(T));
  MPI_Allgatherv(local.data(), my_bytes, MPI_BYTE, out.data(), counts.data(), displs.data(), MPI_BYTE, comm);
  return out;
}

template std::vector<char> all_gather(const std::vector<char>&, MPI_Comm);
template std::vector<int> all_gather(const std::vector<int>&, MPI_Comm);
template std::vector<std::int64_t> all_gather(const std::vector<std::int64_t>&, MPI_Comm);
template std::vector<double> all_gather(const std::vector<double>&, MPI_Comm);

std::vector<double> peak_resident_bytes(MPI_Comm comm) {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return all_gather(std::vector<double>{1024.0 * double(usage.ru_maxrss)}, comm);  // ru_maxrss is in kB on Linux
}

}  // namespace shellfrac::parallel
