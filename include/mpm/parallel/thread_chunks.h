#ifndef mpm_parallel_thread_chunks_h
#define mpm_parallel_thread_chunks_h

#include <deal.II/base/multithread_info.h>
#include <deal.II/base/parallel.h>

#include <algorithm>

namespace MPM
{
  using namespace dealii;

  /// The number of chunks for_each_chunk() cuts @p n items into.
  inline unsigned int
  chunk_count(const unsigned int n, const unsigned int chunk_size)
  {
    return (n + chunk_size - 1) / chunk_size;
  }


  /**
   * The chunk size for a loop over @p n items (cells, points, corners):
   * all of them on one thread; else about eight chunks per thread, for
   * balance, of at least 32 items, so that TBB's cost per chunk (about a
   * microsecond) stays small. The threaded loops of this code give the
   * same results for any chunk size.
   */
  inline unsigned int
  chunk_size_for(const unsigned int n)
  {
    const unsigned int n_threads = MultithreadInfo::n_threads();
    return n_threads == 1 ?
             std::max(n, 1u) :
             std::max(32u, (n + 8 * n_threads - 1) / (8 * n_threads));
  }


  /// Whether for_each_chunk() runs its chunks in order on the calling
  /// thread (one thread, or a single chunk).
  inline bool
  chunks_run_serially(const unsigned int n, const unsigned int chunk_size)
  {
    return chunk_count(n, chunk_size) < 2 || MultithreadInfo::n_threads() == 1;
  }


  /**
   * The threads of one MPI rank work on fixed chunks of a loop, so that
   * what a run computes does not depend on the number of threads.
   *
   * The items [0, @p n) are cut into chunks of @p chunk_size consecutive
   * items, the same cut for any number of threads, and @p body(chunk,
   * begin, end) is called once per chunk: in order on the calling thread
   * if chunks_run_serially() (one thread, 'mpm --threads 1'), otherwise on
   * the threads TBB has (deal.II's parallel::apply_to_subranges()), in any
   * order and concurrently. The body must write only what belongs to its
   * items or to its own chunk (per-chunk sums, lists, extremes); whoever
   * combines the chunks' results afterwards does it in chunk order, so
   * that sums and first-found points are those of the serial loop, bit for
   * bit.
   */
  template <typename Body>
  void
  for_each_chunk(const unsigned int n,
                 const unsigned int chunk_size,
                 const Body        &body)
  {
    const auto run = [&](const unsigned int first, const unsigned int last) {
      for (unsigned int chunk = first; chunk < last; ++chunk)
        body(chunk, chunk * chunk_size, std::min(n, (chunk + 1) * chunk_size));
    };
    if (chunks_run_serially(n, chunk_size))
      run(0, chunk_count(n, chunk_size));
    else
      parallel::apply_to_subranges(0u, chunk_count(n, chunk_size), run, 1);
  }


  /**
   * deal.II on one thread while this object lives (the set-up and a
   * repartition: FEValues for the points' volumes and the boundary
   * normals).
   *
   * deal.II's FEValues reuses the Jacobians of the previous cell for a
   * cell that is its translation ("cell similarity") only on one thread;
   * on several it computes them again, which changes the points' volumes
   * and masses at round-off, and a run would depend on the number of
   * threads from its first step.
   */
  class OneThreadScope
  {
  public:
    OneThreadScope()
      : n_threads_outside(MultithreadInfo::n_threads())
    {
      MultithreadInfo::set_thread_limit(1);
    }

    ~OneThreadScope()
    {
      MultithreadInfo::set_thread_limit(n_threads_outside);
    }

    /// The number of threads outside this scope.
    unsigned int
    threads_outside() const
    {
      return n_threads_outside;
    }

    OneThreadScope(const OneThreadScope &) = delete;
    OneThreadScope &
    operator=(const OneThreadScope &) = delete;

  private:
    const unsigned int n_threads_outside;
  };
} // namespace MPM

#endif
