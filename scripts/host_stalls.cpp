// What the host takes from busy vCPUs: each of THREADS threads (pinned one per CPU) times a
// fixed chunk of pure arithmetic (~1.7 us here) back to back for SECONDS, with the time stamp counter.
// A chunk that takes more than three times the median was interrupted: the time over the
// median is what the host (or the guest's own interrupts) took. It prints, per thread, the
// share of the wall time taken, how many interruptions, their median length, how strongly
// they keep step with a 1 ms clock (0 = no relation, 1 = every one at the same phase), and,
// with two threads, how many interruptions of one overlap one of the other and the share of
// the time in which either is interrupted. Run it with one thread and with two, alternated:
// what two busy vCPUs lose beyond one, a step whose threads meet every pass cannot win back.
// (Pinning is best effort: on a machine with one CPU the threads run unpinned.)
// docs/performance_log.md, issue 11, twenty-ninth session.
//   g++ -O2 -pthread scripts/host_stalls.cpp -o /tmp/host_stalls
//   /tmp/host_stalls [THREADS=2] [SECONDS=2]
#include <pthread.h>
#include <sched.h>
#include <x86intrin.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <thread>
#include <vector>

namespace {

// An interruption: the time stamp counter span of a chunk less its median work (where in the
// chunk the work fell is not known: the span is placed at the chunk's end, within one chunk).
struct Stall {
  std::uint64_t from, to;
};

// Two dependent multiply-add chains: a fixed time on one core, no memory traffic.
double chunk(double seed) {
  double a = seed, d = 0.5 * seed;
  for (int i = 0; i < 1000; ++i) {
    a = a * 1.0000001 + 1e-9;
    d = d * 0.9999999 + 1e-9;
  }
  return a + d;
}

bool pin(int cpu) {
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(cpu, &set);
  return pthread_setaffinity_np(pthread_self(), sizeof set, &set) == 0;
}

struct Trace {
  std::vector<std::uint64_t> starts;  // each chunk's start, touched before the clock runs
  std::size_t count = 0;
  double sink = 0;
};

void run(int cpu, std::uint64_t until, std::atomic<int>& ready, int threads, Trace& out) {
  pin(cpu);
  ready.fetch_add(1);
  while (ready.load() < threads) {}
  double s = 1.0;
  std::size_t k = 0;
  for (std::uint64_t now = __rdtsc(); now < until && k < out.starts.size(); now = __rdtsc()) {
    out.starts[k++] = now;
    s = chunk(s);
  }
  out.count = k;
  out.sink = s;
}

bool parse(const char* text, long lo, long hi, long& value) {
  char* end = nullptr;
  value = std::strtol(text, &end, 10);
  return end != text && *end == '\0' && value >= lo && value <= hi;
}

}  // namespace

int main(int argc, char** argv) {
  long threads = 2, seconds = 2;
  if ((argc > 1 && !parse(argv[1], 1, 2, threads)) || (argc > 2 && !parse(argv[2], 1, 60, seconds)) || argc > 3) {
    std::fprintf(stderr, "usage: host_stalls [THREADS: 1-2] [SECONDS: 1-60]\n");
    return 2;
  }
  // The counter's rate, from the steady clock over 200 ms.
  const auto c0 = std::chrono::steady_clock::now();
  const std::uint64_t t0 = __rdtsc();
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  const double hz = (__rdtsc() - t0) / std::chrono::duration<double>(std::chrono::steady_clock::now() - c0).count();

  // Room for chunks as short as 0.25 us (a chunk takes ~1.7 us here), its pages faulted in
  // now rather than while the clock runs; a thread that fills it stops early, and is reported.
  const auto room = static_cast<std::size_t>((seconds + 0.3) * 4e6);
  std::vector<Trace> traces(static_cast<std::size_t>(threads));
  for (auto& t : traces) t.starts.assign(room, 1);
  std::atomic<int> ready{0};
  const std::uint64_t until = __rdtsc() + static_cast<std::uint64_t>((seconds + 0.3) * hz);
  std::vector<std::thread> team;
  for (int t = 0; t < threads; ++t)
    team.emplace_back(run, t, until, std::ref(ready), static_cast<int>(threads), std::ref(traces[static_cast<std::size_t>(t)]));
  for (auto& th : team) th.join();
  for (const auto& t : traces)
    if (t.count == room) {
      std::fprintf(stderr, "host_stalls: chunks shorter than 0.25 us filled the record before the time was up\n");
      return 1;
    }

  std::vector<std::vector<Stall>> stalls(traces.size());
  for (std::size_t t = 0; t < traces.size(); ++t) {
    const std::vector<std::uint64_t> e(traces[t].starts.begin(), traces[t].starts.begin() + static_cast<std::ptrdiff_t>(traces[t].count));
    std::vector<std::uint64_t> len;
    for (std::size_t k = 1; k < e.size(); ++k) len.push_back(e[k] - e[k - 1]);
    std::vector<std::uint64_t> sorted = len;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const std::uint64_t median = sorted[sorted.size() / 2];
    std::uint64_t taken = 0;
    double c = 0, s = 0;
    const double period = 1e-3 * hz;
    for (std::size_t k = 0; k < len.size(); ++k)
      if (len[k] > 3 * median) {
        stalls[t].push_back({e[k + 1] - (len[k] - median), e[k + 1]});
        taken += len[k] - median;
        c += std::cos(2 * M_PI * std::fmod(static_cast<double>(e[k]), period) / period);
        s += std::sin(2 * M_PI * std::fmod(static_cast<double>(e[k]), period) / period);
      }
    const double wall = static_cast<double>(e.back() - e.front());
    std::vector<std::uint64_t> lengths;
    for (const auto& st : stalls[t]) lengths.push_back(st.to - st.from);
    std::sort(lengths.begin(), lengths.end());
    const std::size_t n = lengths.size();
    std::printf("thread %zu: chunk %.2f us, taken %.2f %% of %.2f s in %zu interruptions (%.0f/s), "
                "median %.1f us, p90 %.1f us; 1 ms coherence %.2f\n",
                t, median / hz * 1e6, 100.0 * taken / wall, wall / hz, n, n / (wall / hz),
                n ? lengths[n / 2] / hz * 1e6 : 0.0, n ? lengths[n * 9 / 10] / hz * 1e6 : 0.0,
                n ? std::hypot(c, s) / n : 0.0);
  }
  if (stalls.size() == 2) {
    // Interruptions of thread 0 whose span overlaps one of thread 1's, and the share of the
    // wall time in which at least one thread was interrupted: what a program whose threads
    // meet every few microseconds loses, against one thread's own share.
    std::size_t both = 0, j = 0;
    const auto& a = stalls[0];
    const auto& b = stalls[1];
    for (const auto& st : a) {
      while (j < b.size() && b[j].to < st.from) ++j;
      if (j < b.size() && b[j].from <= st.to) ++both;
    }
    std::vector<std::pair<std::uint64_t, std::uint64_t>> spans;
    for (const auto& v : stalls)
      for (const auto& st : v) spans.emplace_back(st.from, st.to);
    std::sort(spans.begin(), spans.end());
    std::uint64_t covered = 0, lo = 0, hi = 0;
    for (const auto& [from, to] : spans) {
      if (from > hi) {
        covered += hi - lo;
        lo = from;
        hi = to;
      } else {
        hi = std::max(hi, to);
      }
    }
    covered += hi - lo;
    const auto& e = traces[0];
    const double wall = static_cast<double>(e.starts[e.count - 1] - e.starts[0]);
    std::printf("overlapping: %zu of %zu and %zu; either thread interrupted %.2f %% of the time\n",
                both, a.size(), b.size(), 100.0 * covered / wall);
  }
  return 0;
}
