// shellfrac_machine_limits: the machine's limits that the roofline of the step compares with
// (docs/performance.md, "Roofline"). Not a test.
//   shellfrac_machine_limits [--threads T] [--mib M]
// Prints, for 1 and for T threads (default: the hardware's), each one working on its own data:
//   triad_GBps          a[i] = b[i] + s c[i] over three arrays of M MiB each (default 256, far beyond the caches),
//                       counted as STREAM counts it: 24 bytes per i (the write-allocate read not counted); best
//                       of 10 passes, summed over the threads;
//   scalar_GFLOPs       x = x * a + b in 12 independent chains of scalar doubles, mul and add separate (the
//                       instructions of shellfrac's default build: SSE2 scalar, no FMA);
//   avx2_fma_GFLOPs     the same in 4-wide vectors with fused multiply-add, where the CPU has AVX2 and FMA;
//   avx512_fma_GFLOPs   the same in 8-wide vectors, where the CPU has AVX-512F.
// 2 flops per multiply-add either way. Exit code 2 on a usage error.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// Runs f(thread) on `threads` threads at once and returns the wall time of the slowest.
template <class F>
double on_threads(int threads, F&& f) {
  std::vector<std::thread> pool;
  const auto t0 = Clock::now();
  for (int k = 0; k < threads; ++k) pool.emplace_back([&, k] { f(k); });
  for (auto& t : pool) t.join();
  return seconds_since(t0);
}

/// STREAM triad bandwidth in GB/s (24 bytes per element), best of `passes`, each thread on its own arrays.
double triad_gbps(int threads, std::size_t n, int passes) {
  std::vector<std::vector<double>> a(threads), b(threads), c(threads);
  on_threads(threads, [&](int k) {  // first touch by the thread that uses them
    a[k].assign(n, 0.0), b[k].assign(n, 1.0), c[k].assign(n, 2.0);
  });
  double best = 1e300;
  for (int p = 0; p < passes; ++p)
    best = std::min(best, on_threads(threads, [&](int k) {
                      double* __restrict x = a[k].data();
                      const double* __restrict y = b[k].data();
                      const double* __restrict z = c[k].data();
                      for (std::size_t i = 0; i < n; ++i) x[i] = y[i] + 3.0 * z[i];
                    }));
  double check = 0;
  for (int k = 0; k < threads; ++k) check += a[k][n / 2];
  if (check != 7.0 * threads) std::fprintf(stderr, "triad check failed\n");
  return 24.0 * double(n) * threads / best / 1e9;
}

constexpr int chains = 12;  // independent dependency chains: enough to cover the FP latency

/// Scalar multiply-adds (separate mul and add, as the default build emits them); returns the result so that
/// the work is not removed.
__attribute__((noinline, optimize("no-tree-vectorize", "no-tree-slp-vectorize"))) double scalar_chains(long iterations, double a, double b) {
  double x[chains];
  for (int c = 0; c < chains; ++c) x[c] = 1.0 + c * 1e-3;
  for (long i = 0; i < iterations; ++i)
    for (int c = 0; c < chains; ++c) x[c] = x[c] * a + b;
  double s = 0;
  for (double v : x) s += v;
  return s;
}

typedef double v4 __attribute__((vector_size(32)));
typedef double v8 __attribute__((vector_size(64)));

__attribute__((noinline, target("avx2,fma"))) double avx2_chains(long iterations, double a, double b) {
  v4 x[chains];
  const v4 va = {a, a, a, a}, vb = {b, b, b, b};
  for (int c = 0; c < chains; ++c) x[c] = v4{1.0, 1.0, 1.0, 1.0} + c * 1e-3;
  for (long i = 0; i < iterations; ++i)
    for (int c = 0; c < chains; ++c) x[c] = __builtin_ia32_vfmaddpd256(x[c], va, vb);
  double s = 0;
  for (const v4& v : x) s += v[0] + v[1] + v[2] + v[3];
  return s;
}

__attribute__((noinline, target("avx512f"))) double avx512_chains(long iterations, double a, double b) {
  v8 x[chains];
  const v8 va = {a, a, a, a, a, a, a, a}, vb = {b, b, b, b, b, b, b, b};
  for (int c = 0; c < chains; ++c) x[c] = v8{1, 1, 1, 1, 1, 1, 1, 1} + c * 1e-3;
  for (long i = 0; i < iterations; ++i)
    for (int c = 0; c < chains; ++c) x[c] = __builtin_ia32_vfmaddpd512_mask(x[c], va, vb, 0xff, 4);
  double s = 0;
  for (const v8& v : x)
    for (int l = 0; l < 8; ++l) s += v[l];
  return s;
}

/// GFLOP/s of `chain` (lanes doubles per chain element) on `threads` threads, best of 3.
template <class Chain>
double gflops(int threads, int lanes, Chain&& chain) {
  const long iterations = 50'000'000;
  double best = 1e300;
  std::vector<double> sink(threads);
  for (int p = 0; p < 3; ++p)
    best = std::min(best, on_threads(threads, [&](int k) { sink[k] = chain(iterations, 0.999999, 1e-6); }));
  if (sink[0] == 12345.678) std::printf("#\n");  // keeps the result alive
  return 2.0 * chains * lanes * double(iterations) * threads / best / 1e9;
}

}  // namespace

int main(int argc, char** argv) {
  int threads = int(std::max(1u, std::thread::hardware_concurrency()));
  long mib = 256;
  for (int i = 1; i < argc; ++i) {
    const bool has_value = i + 1 < argc;
    if (!std::strcmp(argv[i], "--threads") && has_value) threads = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--mib") && has_value) mib = std::atol(argv[++i]);
    else {
      std::fprintf(stderr, "usage: shellfrac_machine_limits [--threads T] [--mib M]\n");
      return 2;
    }
  }
  if (threads < 1 || mib < 1) {
    std::fprintf(stderr, "shellfrac_machine_limits: --threads and --mib must be positive\n");
    return 2;
  }
  const std::size_t n = std::size_t(mib) * 1024 * 1024 / sizeof(double);
  __builtin_cpu_init();
  const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  const bool avx512 = __builtin_cpu_supports("avx512f");
  std::vector<int> counts = {1};
  if (threads > 1) counts.push_back(threads);
  for (int t : counts) {
    std::printf("threads=%d triad_GBps=%.2f", t, triad_gbps(t, n, 10));
    std::printf(" scalar_GFLOPs=%.2f", gflops(t, 1, scalar_chains));
    if (avx2) std::printf(" avx2_fma_GFLOPs=%.2f", gflops(t, 4, avx2_chains));
    if (avx512) std::printf(" avx512_fma_GFLOPs=%.2f", gflops(t, 8, avx512_chains));
    std::printf("\n");
  }
  return 0;
}
