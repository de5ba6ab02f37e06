// The triangular solves of a supernodal Cholesky factor A = P^T L L^T P for k right-hand sides at once,
// split over threads by subtrees of the supernodal elimination tree. Internal to SparseCholesky, which
// owns the CHOLMOD factor this reads.
//
// Why hand-written: CHOLMOD's own solve (cholmod_solve2) calls the BLAS per supernode, and Debian's
// reference BLAS spends most of an ARAP global step in per-call overhead and in loops that reload each
// factor entry once per right-hand side; CHOLMOD's solve is also serial. No Debian package offers a
// supernodal solve that applies each entry of L to all k columns at once and runs on several threads.
// Here the right-hand sides are stored row-major (the k values of a row side by side), each entry of L is
// read once per pass and applied to all k columns in registers, and independent subtrees run on
// different threads.
//
// Layout (CHOLMOD's, cholmod_core.h): supernode s holds the consecutive columns super[s] .. super[s+1]-1;
// its row indices are s_rows[pi[s] .. pi[s+1]), the first (super[s+1]-super[s]) being those columns
// themselves; its values are the column-major (rows x columns) block at x + px[s]. perm maps the row i
// of L to the row perm[i] of A.
#pragma once
#include <Eigen/Core>

#include <cstddef>
#include <optional>
#include <vector>

struct cholmod_factor_struct; // cholmod_factor, without SuiteSparse's header

namespace iarap::detail {

// A supernodal LL^T factor as plain arrays; the arrays stay owned by the factor (CHOLMOD's).
struct SupernodalFactorView {
  int n = 0;                   // rows of A
  int nsuper = 0;              // supernodes
  const int* super = nullptr;  // nsuper + 1: first column of each supernode
  const int* pi = nullptr;     // nsuper + 1: start of each supernode's row indices in s_rows
  const int* px = nullptr;     // nsuper + 1: start of each supernode's values in x
  const int* s_rows = nullptr; // row indices
  const double* x = nullptr;   // values
  const int* perm = nullptr;   // n: row i of L is row perm[i] of A
};

// The view of a CHOLMOD factor when it is supernodal LL^T with int indices and double values (what
// Eigen's CholmodSupernodalLLT makes); nullopt otherwise.
std::optional<SupernodalFactorView> supernodal_factor_view(const cholmod_factor_struct* L);

// Who does which supernode with `bins` parts (bins = 1: everything in order on one thread). Supernodes
// split into the top part (closed under "parent of", done on one thread) and subtrees hanging below it,
// each subtree in one bin; `threads` threads take the bins as they come free. A subtree's supernode
// updates rows of its own subtree and rows of the top part: the latter go to the bin's own accumulator
// (top_slot gives the accumulator row), summed in bin order before the top part runs, so no two threads
// write one row and the result does not depend on which thread ran which bin.
struct SupernodalSchedule {
  int bins = 1;
  int threads = 1;
  std::vector<std::vector<int>> bin_supernodes; // per bin, ascending (children before parents)
  std::vector<int> top;                         // top part, ascending
  std::vector<int> inside_rows; // per supernode: how many of its below-diagonal rows are not top rows
  std::vector<int> top_slot;    // per column of L: its accumulator row if a top column, else -1
  int top_columns = 0;
};

// Persistent workspaces of a solve: reused from call to call (no allocation once they have grown).
struct SupernodalWorkspace {
  std::vector<double> rows;        // n x (up to 4) right-hand sides, row-major, in L's row order
  std::vector<double> accumulator; // bins x top_columns x (up to 4)
};

// The plan of the solves for one factor: elimination tree of the supernodes and per-thread schedule.
class SupernodalSolve {
public:
  // Waking a team and the barriers between the phases of a parallel solve, in the cost model's units
  // (one entry of L applied to the right-hand sides, about a nanosecond): a few microseconds.
  static constexpr double kParallelOverhead = 5000.0;

  // Builds the supernodal elimination tree of L (the parent of a supernode is the one holding its first
  // below-diagonal row) and the schedule for `threads` threads. A parallel schedule is chosen only when
  // its estimated time, parallel_overhead included, beats one thread's.
  SupernodalSolve(const SupernodalFactorView& L, int threads, double parallel_overhead = kParallelOverhead);

  // X (n x k, resized) with A X = B, k >= 1, on the schedule for `threads` threads; rebuilds the stored
  // schedule when `threads` differs from the one it was built for. With `gather`, row i of L is row
  // gather[i] of B and X instead of perm[i] (B in another row order: SparseCholesky::gather_rows).
  void solve(const Eigen::MatrixXd& B, Eigen::MatrixXd& X, int threads, SupernodalWorkspace& ws,
             const int* gather = nullptr);
  // The same on a schedule for `threads` threads made for this call if the stored one is for another
  // count (so the two calls agree bit for bit at one thread count). Safe to call concurrently.
  void solve(const Eigen::MatrixXd& B, Eigen::MatrixXd& X, int threads, SupernodalWorkspace& ws) const;

  // False when L is not laid out as described above (diagonal rows not the supernode's columns, or
  // below-diagonal rows not ascending below them): the caller must then solve another way.
  bool usable() const { return usable_; }
  // The schedule in use (for tests and diagnostics).
  const SupernodalSchedule& schedule() const { return schedule_; }
  // Bytes of the plan (tree, costs, schedule); the factor it reads is the caller's.
  std::size_t memory_bytes() const;

private:
  SupernodalSchedule make_schedule(int threads) const;

  SupernodalFactorView L_;
  std::vector<int> parent_;  // per supernode, -1 for a root
  std::vector<double> work_; // per supernode: entries of L it reads plus a per-supernode overhead
  double parallel_overhead_;
  bool usable_ = true;
  int schedule_threads_ = 1; // the thread count schedule_ was made for
  SupernodalSchedule schedule_;
};

// A X = B on the given schedule (see SupernodalSolve::solve).
void supernodal_solve(const SupernodalFactorView& L, const SupernodalSchedule& schedule,
                      const Eigen::MatrixXd& B, Eigen::MatrixXd& X, SupernodalWorkspace& ws);

} // namespace iarap::detail
