#pragma once
/// \file parallel.hpp
/// The thin layer over raw MPI used by shellfrac (convention: no raw MPI calls elsewhere except the
/// distributed mesh and the I/O package). Collectives here must be called on every rank.
#include <mpi.h>

#include <cstdint>
#include <cstring>
#include <functional>
#include <string>
#include <type_traits>
#include <vector>

namespace shellfrac::parallel {

/// Rank of this process in comm.
int rank(MPI_Comm comm = MPI_COMM_WORLD);
/// Number of ranks in comm.
int size(MPI_Comm comm = MPI_COMM_WORLD);

/// Byte buffer writer for broadcasting plain data structures.
class ByteWriter {
 public:
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* p = reinterpret_cast<const char*>(&v);
    buf_.insert(buf_.end(), p, p + sizeof(T));
  }
  template <class T>
  void put_vector(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    put<std::uint64_t>(v.size());
    const auto* p = reinterpret_cast<const char*>(v.data());
    buf_.insert(buf_.end(), p, p + sizeof(T) * v.size());
  }
  void put_string(const std::string& s) {
    put<std::uint64_t>(s.size());
    buf_.insert(buf_.end(), s.begin(), s.end());
  }
  std::vector<char>& buffer() { return buf_; }

 private:
  std::vector<char> buf_;
};

/// Byte buffer reader matching ByteWriter.
class ByteReader {
 public:
  explicit ByteReader(const std::vector<char>& buf) : buf_(buf) {}
  template <class T>
  T get() {
    T v;
    std::memcpy(&v, take(sizeof(T)), sizeof(T));
    return v;
  }
  template <class T>
  std::vector<T> get_vector() {
    const auto n = get<std::uint64_t>();
    std::vector<T> v(n);
    if (n > 0) std::memcpy(v.data(), take(sizeof(T) * n), sizeof(T) * n);
    return v;
  }
  std::string get_string() {
    const auto n = get<std::uint64_t>();
    return std::string(take(n), n);
  }
  /// Whether everything has been read.
  bool done() const { return pos_ >= buf_.size(); }

 private:
  const char* take(std::size_t n);
  const std::vector<char>& buf_;
  std::size_t pos_ = 0;
};

/// Broadcasts a byte buffer from root (size first). Collective.
void broadcast(std::vector<char>& buf, int root = 0, MPI_Comm comm = MPI_COMM_WORLD);
/// Broadcasts a string from root. Collective.
void broadcast(std::string& s, int root = 0, MPI_Comm comm = MPI_COMM_WORLD);

/// Broadcasts a vector of trivially copyable values from root. Collective.
template <class T>
void broadcast_vector(std::vector<T>& v, int root = 0, MPI_Comm comm = MPI_COMM_WORLD) {
  ByteWriter w;
  if (rank(comm) == root) w.put_vector(v);
  broadcast(w.buffer(), root, comm);
  if (rank(comm) != root) v = ByteReader(w.buffer()).get_vector<T>();
}

/// Runs fn on root only. If it throws, every rank throws the same kind of exception (InputError, OutputError or Error)
/// with the same message, so that all ranks agree and none hangs. Collective.
void on_root_then_agree(const std::function<void()>& fn, int root = 0, MPI_Comm comm = MPI_COMM_WORLD);

/// Runs fn on every rank; if it throws on any rank, every rank throws the message of the lowest failing
/// rank (prefixed with that rank when np > 1). Collective.
void on_all_then_agree(const std::function<void()>& fn, MPI_Comm comm = MPI_COMM_WORLD);

/// Logical OR over ranks. Collective.
bool any(bool local, MPI_Comm comm = MPI_COMM_WORLD);
/// Sum over ranks. Collective.
std::int64_t sum(std::int64_t local, MPI_Comm comm = MPI_COMM_WORLD);
/// Max over ranks. Collective.
double max(double local, MPI_Comm comm = MPI_COMM_WORLD);
/// Sends send[q] to rank q (one vector per rank) and returns what every rank sent here, concatenated in rank order.
/// Collective.
std::vector<double> all_to_all(const std::vector<std::vector<double>>& send, MPI_Comm comm = MPI_COMM_WORLD);
/// Sends send[q] to rank q (one vector per rank) and returns what every rank sent here, concatenated in rank order;
/// counts[q] is the number of values that came from rank q. `send` is consumed (each vector freed once packed, so
/// the peak is about twice what goes out or comes in, not three times). T is trivially copyable and goes as bytes
/// (at most 2^31 - 1 bytes to and from a rank in one call: Error otherwise). Collective.
template <class T>
std::vector<T> exchange(std::vector<std::vector<T>>&& send, std::vector<int>& counts, MPI_Comm comm = MPI_COMM_WORLD);
/// exchange() on bytes: `out` holds the bytes for rank 0, then rank 1, ...: send_bytes[q] of them for rank q;
/// `allocate(total)` returns room for the total received, filled rank by rank; received_bytes[q] from rank q.
void exchange_bytes(const char* out, const std::vector<std::size_t>& send_bytes,
                    const std::function<char*(std::size_t)>& allocate, std::vector<std::size_t>& received_bytes,
                    MPI_Comm comm);
/// Gathers a variable-length vector of T from every rank onto every rank (rank order). Collective.
template <class T>
std::vector<T> all_gather(const std::vector<T>& local, MPI_Comm comm = MPI_COMM_WORLD);

template <class T>
std::vector<T> exchange(std::vector<std::vector<T>>&& send, std::vector<int>& counts, MPI_Comm comm) {
  static_assert(std::is_trivially_copyable_v<T>);
  std::vector<T> out;
  std::vector<std::size_t> send_bytes(send.size()), received_bytes;
  std::size_t total = 0;
  for (const auto& v : send) total += v.size();
  out.reserve(total);
  for (std::size_t q = 0; q < send.size(); ++q) {
    out.insert(out.end(), send[q].begin(), send[q].end());
    send_bytes[q] = send[q].size() * sizeof(T);
    std::vector<T>().swap(send[q]);
  }
  std::vector<T> in;
  exchange_bytes(
      reinterpret_cast<const char*>(out.data()), send_bytes,
      [&in](std::size_t bytes) {
        in.resize(bytes / sizeof(T));
        return reinterpret_cast<char*>(in.data());
      },
      received_bytes, comm);
  counts.assign(received_bytes.size(), 0);
  for (std::size_t q = 0; q < received_bytes.size(); ++q) counts[q] = static_cast<int>(received_bytes[q] / sizeof(T));
  return in;
}

/// The peak resident memory of each rank so far [bytes] (getrusage), in rank order, on every rank. Collective.
std::vector<double> peak_resident_bytes(MPI_Comm comm = MPI_COMM_WORLD);

}  // namespace shellfrac::parallel
