#include "supernodal_solve.h"

#include <cholmod.h>
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <optional>
#include <queue>
#include <thread>
#include <utility>

namespace iarap::detail {

namespace {

// Right-hand sides solved together: G values of a row side by side, so that one load of an entry of L
// serves all of them (k = 3 coordinates in the ARAP global step).
constexpr int kMaxGroup = 4;
// Columns of L applied per sweep over a supernode's rows: J x G running values stay in registers while
// J columns are streamed side by side.
constexpr int kColumnBlock = 4;
// Parts of the subtrees per thread in a parallel solve (see make_schedule).
constexpr int kBinsPerThread = 4;
// How long a waiting thread spins before it yields its core at each further check. Short: a long spin
// costs whole time slices when the two threads share one core (another process on the other); measured
// on beetle, a spin of some 0.3 ms made the 2-thread solve 2.0 ms against 1.2 ms on one thread then.
constexpr std::chrono::microseconds kSpinBeforeYield{50};

// Cost model of the schedule, in units of one entry of L applied to the right-hand sides: a supernode
// also pays for its row indices and a fixed overhead (the parallel solve's own: kParallelOverhead).
constexpr double kRowCost = 2.0;
constexpr double kSupernodeCost = 16.0;

// t -= sum_j L(i, j) yy[j] over the block's J columns (column j at Lj + j * nrow).
template <int G, int J>
inline void subtract_row(const double* Lj, int nrow, int i, const double (&yy)[J][G], double* t) {
  double sum[G];
  for (int c = 0; c < G; ++c) sum[c] = Lj[i] * yy[0][c];
  for (int j = 1; j < J; ++j)
    for (int c = 0; c < G; ++c) sum[c] += Lj[j * nrow + i] * yy[j][c];
  for (int c = 0; c < G; ++c) t[c] -= sum[c];
}

// Forward update by J solved columns y of a supernode: rows [ncol, inside_end) are W's, the rest top rows
// that go to the accumulator acc (row top_slot[r] for row r of L).
template <int G, int J>
void forward_block(const double* Lj, int nrow, const int* rows, int ncol, int inside_end, const double* y,
                   double* W, double* acc, const int* top_slot) {
  double yy[J][G];
  for (int j = 0; j < J; ++j)
    for (int c = 0; c < G; ++c) yy[j][c] = y[j * G + c];
  for (int i = ncol; i < inside_end; ++i)
    subtract_row<G, J>(Lj, nrow, i, yy, W + static_cast<std::ptrdiff_t>(rows[i]) * G);
  for (int i = inside_end; i < nrow; ++i)
    subtract_row<G, J>(Lj, nrow, i, yy, acc + static_cast<std::ptrdiff_t>(top_slot[rows[i]]) * G);
}

// L y = b for supernode s: its diagonal block by forward substitution, then its below-diagonal rows
// updated (the first `inside` of them in W, the others, top rows, in acc).
template <int G>
void forward_supernode(const SupernodalFactorView& L, int s, int inside, double* W, double* acc,
                       const int* top_slot) {
  const int k1 = L.super[s], ncol = L.super[s + 1] - k1;
  const int* rows = L.s_rows + L.pi[s];
  const int nrow = L.pi[s + 1] - L.pi[s];
  const double* Ls = L.x + L.px[s];
  double* y = W + static_cast<std::ptrdiff_t>(k1) * G;
  for (int j = 0; j < ncol; ++j) {
    const double* col = Ls + static_cast<std::ptrdiff_t>(j) * nrow;
    double yj[G];
    for (int c = 0; c < G; ++c) yj[c] = y[j * G + c] /= col[j];
    for (int i = j + 1; i < ncol; ++i)
      for (int c = 0; c < G; ++c) y[i * G + c] -= col[i] * yj[c];
  }
  const int inside_end = ncol + inside;
  for (int j0 = 0; j0 < ncol; j0 += kColumnBlock) {
    const double* Lj = Ls + static_cast<std::ptrdiff_t>(j0) * nrow;
    const double* yb = y + j0 * G;
    switch (std::min(kColumnBlock, ncol - j0)) {
    case 4:
      forward_block<G, 4>(Lj, nrow, rows, ncol, inside_end, yb, W, acc, top_slot);
      break;
    case 3:
      forward_block<G, 3>(Lj, nrow, rows, ncol, inside_end, yb, W, acc, top_slot);
      break;
    case 2:
      forward_block<G, 2>(Lj, nrow, rows, ncol, inside_end, yb, W, acc, top_slot);
      break;
    default:
      forward_block<G, 1>(Lj, nrow, rows, ncol, inside_end, yb, W, acc, top_slot);
    }
  }
}

// x_j -= sum_i L(i, j) x[rows[i]] over the below-diagonal rows, for the block's J columns.
template <int G, int J>
void backward_block(const double* Lj, int nrow, const int* rows, int ncol, const double* W, double* x) {
  double sum[J][G] = {};
  for (int i = ncol; i < nrow; ++i) {
    const double* xr = W + static_cast<std::ptrdiff_t>(rows[i]) * G;
    for (int j = 0; j < J; ++j)
      for (int c = 0; c < G; ++c) sum[j][c] += Lj[j * nrow + i] * xr[c];
  }
  for (int j = 0; j < J; ++j)
    for (int c = 0; c < G; ++c) x[j * G + c] -= sum[j][c];
}

// L^T x = y for supernode s, once every row it names (its ancestors') holds x.
template <int G> void backward_supernode(const SupernodalFactorView& L, int s, double* W) {
  const int k1 = L.super[s], ncol = L.super[s + 1] - k1;
  const int* rows = L.s_rows + L.pi[s];
  const int nrow = L.pi[s + 1] - L.pi[s];
  const double* Ls = L.x + L.px[s];
  double* x = W + static_cast<std::ptrdiff_t>(k1) * G;
  if (nrow > ncol)
    for (int j0 = 0; j0 < ncol; j0 += kColumnBlock) {
      const double* Lj = Ls + static_cast<std::ptrdiff_t>(j0) * nrow;
      double* xb = x + j0 * G;
      switch (std::min(kColumnBlock, ncol - j0)) {
      case 4:
        backward_block<G, 4>(Lj, nrow, rows, ncol, W, xb);
        break;
      case 3:
        backward_block<G, 3>(Lj, nrow, rows, ncol, W, xb);
        break;
      case 2:
        backward_block<G, 2>(Lj, nrow, rows, ncol, W, xb);
        break;
      default:
        backward_block<G, 1>(Lj, nrow, rows, ncol, W, xb);
      }
    }
  for (int j = ncol - 1; j >= 0; --j) {
    const double* col = Ls + static_cast<std::ptrdiff_t>(j) * nrow;
    double v[G];
    for (int c = 0; c < G; ++c) v[c] = x[j * G + c];
    for (int i = j + 1; i < ncol; ++i)
      for (int c = 0; c < G; ++c) v[c] -= col[i] * x[i * G + c];
    for (int c = 0; c < G; ++c) x[j * G + c] = v[c] / col[j];
  }
}

// Waits until `counter` reaches `value` (acquire): spinning for kSpinBeforeYield, then yielding the core
// between checks (a thread of ours waiting for this core then runs at once).
void wait_until(const std::atomic<int>& counter, int value) {
  const auto spin_end = std::chrono::steady_clock::now() + kSpinBeforeYield;
  bool spinning = true;
  for (int check = 1; counter.load(std::memory_order_acquire) < value; ++check) {
    if (spinning && check % 64 == 0) spinning = std::chrono::steady_clock::now() < spin_end;
    if (spinning) {
#if defined(__x86_64__) || defined(__i386__)
      __builtin_ia32_pause();
#endif
    } else {
      std::this_thread::yield();
    }
  }
}

// Columns [c0, c0 + G) of B solved into the same columns of X.
template <int G>
void solve_group(const SupernodalFactorView& L, const SupernodalSchedule& sc, const Eigen::MatrixXd& B,
                 Eigen::Index c0, Eigen::MatrixXd& X, SupernodalWorkspace& ws) {
  const int n = L.n;
  double* W = ws.rows.data();
  const double* b = B.data() + c0 * n;
  double* xout = X.data() + c0 * n;
  const int* perm = L.perm;
  // P b into W (row i of L is row perm[i] of A), and W back out as P^T x.
  auto gather = [&](int i) {
    for (int c = 0; c < G; ++c)
      W[static_cast<std::ptrdiff_t>(i) * G + c] = b[perm[i] + static_cast<std::ptrdiff_t>(c) * n];
  };
  auto scatter = [&](int i) {
    for (int c = 0; c < G; ++c)
      xout[perm[i] + static_cast<std::ptrdiff_t>(c) * n] = W[static_cast<std::ptrdiff_t>(i) * G + c];
  };
  if (sc.bins == 1) {
    for (int i = 0; i < n; ++i) gather(i);
    for (int s = 0; s < L.nsuper; ++s) forward_supernode<G>(L, s, sc.inside_rows[s], W, nullptr, nullptr);
    for (int s = L.nsuper - 1; s >= 0; --s) backward_supernode<G>(L, s, W);
    for (int i = 0; i < n; ++i) scatter(i);
    return;
  }
  const int bins = sc.bins;
  const std::ptrdiff_t bin_stride = static_cast<std::ptrdiff_t>(sc.top_columns) * G;
  double* acc = ws.accumulator.data();
  const int* top_slot = sc.top_slot.data();
  // Each bin gathers and scatters the rows of its own supernodes, the top part's thread those of the top.
  // The last thread out of the forward pass does the top part at once (the counter's acquire-release
  // makes the other threads' rows visible to it) while the others wait for it; the main thread waits for
  // the others' backward passes before the region's join. Both waits spin briefly, then yield: an OpenMP
  // barrier under the tool's passive wait policy (app/omp_wait_policy.cpp) puts the waiting thread to
  // sleep, and waking it costs tens of microseconds on the critical path, twice per solve.
  std::atomic<int> finished{0}, top_done{0}, backward_done{0};
  auto columns = [&](int s, auto&& f) {
    for (int col = L.super[s]; col < L.super[s + 1]; ++col) f(col);
  };
#pragma omp parallel num_threads(sc.threads)
  {
    // Subtrees: each bin writes its own rows and its own accumulator only.
#pragma omp for schedule(dynamic, 1) nowait
    for (int bin = 0; bin < bins; ++bin) {
      double* acc_bin = acc + bin * bin_stride;
      std::fill(acc_bin, acc_bin + bin_stride, 0.0);
      for (const int s : sc.bin_supernodes[bin]) columns(s, gather); // all before their updates arrive
      for (const int s : sc.bin_supernodes[bin])
        forward_supernode<G>(L, s, sc.inside_rows[s], W, acc_bin, top_slot);
    }
    // The top part on one thread: the bins' updates in bin order (each accumulator holds minus the sum of
    // its bin's updates, as the subtraction started from zero), then its forward and backward solves.
    if (finished.fetch_add(1, std::memory_order_acq_rel) + 1 == omp_get_num_threads()) {
      for (const int s : sc.top)
        columns(s, [&](int col) {
          gather(col);
          for (int bin = 0; bin < bins; ++bin) {
            const double* a = acc + bin * bin_stride + static_cast<std::ptrdiff_t>(top_slot[col]) * G;
            for (int c = 0; c < G; ++c) W[static_cast<std::ptrdiff_t>(col) * G + c] += a[c];
          }
        });
      for (const int s : sc.top) forward_supernode<G>(L, s, sc.inside_rows[s], W, nullptr, nullptr);
      for (auto it = sc.top.rbegin(); it != sc.top.rend(); ++it) {
        backward_supernode<G>(L, *it, W);
        columns(*it, scatter);
      }
      top_done.store(1, std::memory_order_release);
    } else {
      wait_until(top_done, 1);
    }
    // Subtrees again, each reading only its own rows and the top part's.
#pragma omp for schedule(dynamic, 1) nowait
    for (int bin = 0; bin < bins; ++bin)
      for (auto it = sc.bin_supernodes[bin].rbegin(); it != sc.bin_supernodes[bin].rend(); ++it) {
        backward_supernode<G>(L, *it, W);
        columns(*it, scatter);
      }
    backward_done.fetch_add(1, std::memory_order_release);
    if (omp_get_thread_num() == 0) wait_until(backward_done, omp_get_num_threads());
  }
}

} // namespace

void supernodal_solve(const SupernodalFactorView& L, const SupernodalSchedule& schedule,
                      const Eigen::MatrixXd& B, Eigen::MatrixXd& X, SupernodalWorkspace& ws) {
  const Eigen::Index k = B.cols();
  if (X.rows() != B.rows() || X.cols() != k) X.resize(B.rows(), k);
  const std::size_t n = static_cast<std::size_t>(L.n);
  const int group = static_cast<int>(std::min<Eigen::Index>(k, kMaxGroup));
  if (ws.rows.size() < n * group) ws.rows.resize(n * group);
  const std::size_t acc_size = static_cast<std::size_t>(schedule.bins) * schedule.top_columns * group;
  if (schedule.bins > 1 && ws.accumulator.size() < acc_size) ws.accumulator.resize(acc_size);
  for (Eigen::Index c0 = 0; c0 < k; c0 += kMaxGroup) {
    switch (std::min<Eigen::Index>(kMaxGroup, k - c0)) {
    case 4:
      solve_group<4>(L, schedule, B, c0, X, ws);
      break;
    case 3:
      solve_group<3>(L, schedule, B, c0, X, ws);
      break;
    case 2:
      solve_group<2>(L, schedule, B, c0, X, ws);
      break;
    default:
      solve_group<1>(L, schedule, B, c0, X, ws);
    }
  }
}

std::optional<SupernodalFactorView> supernodal_factor_view(const cholmod_factor_struct* L) {
  if (!L || !L->is_super || !L->is_ll || L->itype != CHOLMOD_INT || L->xtype != CHOLMOD_REAL ||
      L->dtype != CHOLMOD_DOUBLE || L->nsuper == 0 || !L->super || !L->pi || !L->px || !L->s || !L->x ||
      !L->Perm)
    return std::nullopt;
  SupernodalFactorView view;
  view.n = static_cast<int>(L->n);
  view.nsuper = static_cast<int>(L->nsuper);
  view.super = static_cast<const int*>(L->super);
  view.pi = static_cast<const int*>(L->pi);
  view.px = static_cast<const int*>(L->px);
  view.s_rows = static_cast<const int*>(L->s);
  view.x = static_cast<const double*>(L->x);
  view.perm = static_cast<const int*>(L->Perm);
  return view;
}

SupernodalSolve::SupernodalSolve(const SupernodalFactorView& L, int threads, double parallel_overhead)
    : L_(L), parallel_overhead_(parallel_overhead) {
  const int ns = L.nsuper;
  parent_.assign(ns, -1);
  work_.assign(ns, 0.0);
  // Which supernode holds each column, for the parents.
  std::vector<int> column_owner(L.n, -1);
  for (int s = 0; s < ns && usable_; ++s) {
    const int k1 = L.super[s], k2 = L.super[s + 1], ncol = k2 - k1;
    const int nrow = L.pi[s + 1] - L.pi[s];
    const int* rows = L.s_rows + L.pi[s];
    if (ncol <= 0 || nrow < ncol || k2 > L.n || L.px[s + 1] - L.px[s] < static_cast<long long>(nrow) * ncol) {
      usable_ = false;
      break;
    }
    for (int i = 0; i < nrow && usable_; ++i) {
      const bool diagonal_ok = i >= ncol || rows[i] == k1 + i;
      const bool below_ok = i < ncol || (rows[i] > rows[i - 1] && rows[i] < L.n);
      usable_ = diagonal_ok && below_ok;
    }
    for (int col = k1; col < k2; ++col) column_owner[col] = s;
    work_[s] = static_cast<double>(ncol) * nrow - 0.5 * ncol * (ncol - 1) + kRowCost * nrow + kSupernodeCost;
  }
  usable_ = usable_ && ns >= 1 && L.super[0] == 0 && L.super[ns] == L.n;
  if (!usable_) return;
  for (int s = 0; s < ns; ++s) {
    const int first_below = L.pi[s] + (L.super[s + 1] - L.super[s]);
    if (first_below < L.pi[s + 1]) parent_[s] = column_owner[L.s_rows[first_below]];
  }
  schedule_threads_ = threads;
  schedule_ = make_schedule(threads);
}

namespace {

// Everything on one thread, in supernode order (children before parents).
SupernodalSchedule serial_schedule(const SupernodalFactorView& L) {
  SupernodalSchedule sc;
  sc.inside_rows.resize(L.nsuper);
  for (int s = 0; s < L.nsuper; ++s)
    sc.inside_rows[s] = (L.pi[s + 1] - L.pi[s]) - (L.super[s + 1] - L.super[s]);
  sc.bin_supernodes.assign(1, std::vector<int>(L.nsuper));
  for (int s = 0; s < L.nsuper; ++s) sc.bin_supernodes[0][s] = s;
  return sc;
}

// The elimination tree's subtrees: each supernode's children and the work of its subtree.
struct Subtrees {
  std::vector<double> work;
  std::vector<std::vector<int>> children;
  double total = 0;
};

Subtrees subtrees(const std::vector<int>& parent, const std::vector<double>& work) {
  const int ns = static_cast<int>(parent.size());
  Subtrees t{work, std::vector<std::vector<int>>(ns), 0.0};
  for (int s = 0; s < ns; ++s) { // children come before their parent
    t.total += work[s];
    if (parent[s] >= 0) {
      t.work[parent[s]] += t.work[s];
      t.children[parent[s]].push_back(s);
    }
  }
  return t;
}

using Candidate = std::pair<double, int>; // (subtree work, -supernode): heaviest first, then lowest index

// The top part (closed under "parent of"), as is_top per supernode with its work and the best estimated
// time, or nullopt when no split beats one thread. Subtree-to-thread mapping: starting from the roots, move
// the heaviest subtree's root into the top part while that lowers the estimate top work + max(heaviest
// subtree, subtree work / threads); keep the best.
struct TopPart {
  std::vector<char> is_top;
  double work = 0, best = 0;
};

std::optional<TopPart> choose_top_part(const SupernodalFactorView& L, const std::vector<int>& parent,
                                       const std::vector<double>& work, const Subtrees& tree, int threads,
                                       double parallel_overhead) {
  const int ns = L.nsuper;
  std::priority_queue<Candidate> candidates;
  double candidate_work = 0, top_work = 0, top_columns = 0;
  for (int s = 0; s < ns; ++s)
    if (parent[s] < 0) {
      candidates.push({tree.work[s], -s});
      candidate_work += tree.work[s];
    }
  std::vector<int> moved; // supernodes moved to the top part, in order
  double best = tree.total;
  std::size_t best_moves = 0;
  bool parallel = false;
  while (!candidates.empty() && top_work < best) {
    const double estimate = top_work + std::max(candidates.top().first, candidate_work / threads) +
                            top_columns * threads + parallel_overhead;
    if (estimate < best && candidates.size() >= 2) {
      best = estimate;
      best_moves = moved.size();
      parallel = true;
    }
    const int s = -candidates.top().second;
    candidates.pop();
    candidate_work -= tree.work[s];
    top_work += work[s];
    top_columns += L.super[s + 1] - L.super[s];
    moved.push_back(s);
    for (const int child : tree.children[s]) {
      candidates.push({tree.work[child], -child});
      candidate_work += tree.work[child];
    }
  }
  if (!parallel) return std::nullopt;
  TopPart top{std::vector<char>(ns, 0), 0.0, best};
  for (std::size_t m = 0; m < best_moves; ++m) {
    top.is_top[moved[m]] = 1;
    top.work += work[moved[m]];
  }
  return top;
}

// The subtrees below the top part as parts for the threads. More parts than threads, taken by whichever
// thread is free (dynamic scheduling): the cost model's errors and a thread the scheduler holds back even
// out. Subtrees too heavy for one part are split further (their roots join the top part) while that adds at
// most 2% of the estimate to the top part.
std::priority_queue<Candidate> split_into_parts(const std::vector<int>& parent,
                                                const std::vector<double>& work, const Subtrees& tree,
                                                int max_bins, TopPart& top) {
  const int ns = static_cast<int>(parent.size());
  std::priority_queue<Candidate> parts;
  double candidate_work = 0;
  for (int s = 0; s < ns; ++s)
    if (!top.is_top[s] && (parent[s] < 0 || top.is_top[parent[s]])) {
      parts.push({tree.work[s], -s});
      candidate_work += tree.work[s];
    }
  const double top_limit = top.work + 0.02 * top.best;
  while (static_cast<int>(parts.size()) < max_bins) {
    const int s = -parts.top().second;
    if (tree.work[s] <= candidate_work / max_bins || top.work + work[s] > top_limit) break;
    parts.pop();
    top.is_top[s] = 1;
    top.work += work[s];
    candidate_work -= tree.work[s];
    for (const int child : tree.children[s]) {
      parts.push({tree.work[child], -child});
      candidate_work += tree.work[child];
    }
    if (parts.empty()) break;
  }
  return parts;
}

// Heaviest subtree first onto the least loaded bin (LPT); every supernode below the top part gets its
// subtree root's bin. Returns the bin of each supernode (-1 for the top part) and the load of each bin.
std::pair<std::vector<int>, std::vector<double>> assign_bins(const std::vector<int>& parent,
                                                             const Subtrees& tree, const TopPart& top,
                                                             int max_bins,
                                                             std::priority_queue<Candidate> parts) {
  const int ns = static_cast<int>(parent.size());
  std::vector<double> load(std::min<std::size_t>(max_bins, parts.size()), 0.0);
  std::vector<int> bin(ns, -1);
  for (; !parts.empty(); parts.pop()) {
    const int r = -parts.top().second;
    const int target = static_cast<int>(std::min_element(load.begin(), load.end()) - load.begin());
    load[target] += tree.work[r];
    bin[r] = target;
  }
  for (int s = ns - 1; s >= 0; --s)
    if (!top.is_top[s] && bin[s] < 0) bin[s] = bin[parent[s]];
  return {std::move(bin), std::move(load)};
}

// The schedule from the bins: parts renumbered in decreasing load (the order in which the threads take
// them), the top part's accumulator slots, and each subtree supernode's rows split into its own subtree's
// (first) and the top part's (higher columns, as ancestors of the subtree's root). nullopt when the bins are
// fewer than 2 or the rows are not laid out so (not a postordered tree after all).
std::optional<SupernodalSchedule> fill_schedule(const SupernodalFactorView& L, const TopPart& top,
                                                const std::vector<int>& bin, const std::vector<double>& load,
                                                int threads) {
  const int ns = L.nsuper;
  SupernodalSchedule sc = serial_schedule(L);
  std::vector<int> by_load(load.size());
  for (std::size_t b = 0; b < load.size(); ++b) by_load[b] = static_cast<int>(b);
  std::stable_sort(by_load.begin(), by_load.end(), [&](int a, int b) { return load[a] > load[b]; });
  std::vector<int> renumber(load.size(), -1);
  sc.bins = 0;
  for (const int b : by_load)
    if (load[b] > 0) renumber[b] = sc.bins++;
  if (sc.bins < 2) return std::nullopt;
  sc.threads = std::min(threads, sc.bins);
  sc.bin_supernodes.assign(sc.bins, {});
  sc.top_slot.assign(L.n, -1);
  for (int s = 0; s < ns; ++s) {
    if (top.is_top[s]) {
      sc.top.push_back(s);
      for (int col = L.super[s]; col < L.super[s + 1]; ++col) sc.top_slot[col] = sc.top_columns++;
    } else {
      sc.bin_supernodes[renumber[bin[s]]].push_back(s);
    }
  }
  for (int s = 0; s < ns; ++s) {
    if (top.is_top[s]) continue;
    const int ncol = L.super[s + 1] - L.super[s];
    const int* rows = L.s_rows + L.pi[s];
    int inside = 0;
    while (inside < sc.inside_rows[s] && sc.top_slot[rows[ncol + inside]] < 0) ++inside;
    for (int i = inside; i < sc.inside_rows[s]; ++i)
      if (sc.top_slot[rows[ncol + i]] < 0) return std::nullopt;
    sc.inside_rows[s] = inside;
  }
  return sc;
}

} // namespace

SupernodalSchedule SupernodalSolve::make_schedule(int threads) const {
  if (threads <= 1 || L_.nsuper < 2) return serial_schedule(L_);
  const Subtrees tree = subtrees(parent_, work_);
  std::optional<TopPart> top = choose_top_part(L_, parent_, work_, tree, threads, parallel_overhead_);
  if (!top) return serial_schedule(L_);
  const int max_bins = kBinsPerThread * threads;
  std::priority_queue<Candidate> parts = split_into_parts(parent_, work_, tree, max_bins, *top);
  const auto [bin, load] = assign_bins(parent_, tree, *top, max_bins, std::move(parts));
  std::optional<SupernodalSchedule> sc = fill_schedule(L_, *top, bin, load, threads);
  return sc ? std::move(*sc) : serial_schedule(L_);
}

void SupernodalSolve::solve(const Eigen::MatrixXd& B, Eigen::MatrixXd& X, int threads,
                            SupernodalWorkspace& ws, const int* gather) {
  if (threads != schedule_threads_) {
    schedule_ = make_schedule(threads);
    schedule_threads_ = threads;
  }
  SupernodalFactorView L = L_;
  if (gather) L.perm = gather;
  supernodal_solve(L, schedule_, B, X, ws);
}

void SupernodalSolve::solve(const Eigen::MatrixXd& B, Eigen::MatrixXd& X, int threads,
                            SupernodalWorkspace& ws) const {
  if (threads == schedule_threads_) {
    supernodal_solve(L_, schedule_, B, X, ws);
    return;
  }
  supernodal_solve(L_, make_schedule(threads), B, X, ws);
}

std::size_t SupernodalSolve::memory_bytes() const {
  std::size_t bytes = parent_.capacity() * sizeof(int) + work_.capacity() * sizeof(double);
  for (const auto& bin : schedule_.bin_supernodes) bytes += bin.capacity() * sizeof(int);
  bytes += (schedule_.top.capacity() + schedule_.inside_rows.capacity() + schedule_.top_slot.capacity()) *
           sizeof(int);
  return bytes;
}

} // namespace iarap::detail
