// Memory bandwidth of this machine, one core: a streaming copy (and a
// streaming triad a = b + s c) of arrays much larger than the caches, the
// best of several repetitions, in GB/s counting bytes read plus written.
// The MPM step's particle-steps per second are compared with it in
// doc/performance.md.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

int
main()
{
  const std::size_t   n = 1u << 25; // 32 Mi doubles = 256 MB per array
  std::vector<double> a(n, 1.), b(n, 2.), c(n, 3.);
  double              best_copy = 0, best_triad = 0;
  for (int repetition = 0; repetition < 5; ++repetition)
    {
      auto start = std::chrono::steady_clock::now();
      std::copy(b.begin(), b.end(), a.begin());
      double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
      best_copy = std::max(best_copy, 2. * n * sizeof(double) / seconds / 1e9);

      start = std::chrono::steady_clock::now();
      for (std::size_t i = 0; i < n; ++i)
        a[i] = b[i] + 0.5 * c[i];
      seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
      best_triad = std::max(best_triad, 3. * n * sizeof(double) / seconds / 1e9);
    }
  std::printf("stream copy:  %.1f GB/s\nstream triad: %.1f GB/s\n(check %g)\n",
              best_copy,
              best_triad,
              a[n / 2]);
}
