// What it costs to hand N cache lines from CPU 0 to CPU 1, as a two-thread runout step hands
// the discs and pushes at its block boundary (~75 and ~38 lines a pass; docs/performance.md,
// "Why the slow mode falls short"), and whether the writer or the reader can make it cheaper.
// CPU 0 writes the N lines and raises a flag; CPU 1 reads them and answers; the time is CPU 0's,
// from its first store to the answer (one round trip of the flags plus the lines' transfer).
// Modes: plain; the writer writes each line back (clwb) or flushes it (clflushopt) before the
// flag, so the reader may find it in memory rather than in the other core's cache; the reader
// prefetches all N lines before reading them; the reader flushes them after reading, so the
// writer's next stores find no copy to invalidate.
//   g++ -O2 -mclwb -mclflushopt -pthread scripts/line_handoff_probe.cpp -o /tmp/line_handoff_probe
//   /tmp/line_handoff_probe LINES [HANDOFFS=20000] [MODE=plain|clwb|flush|prefetch|reader-flush]
//   -> "lines 75 mode plain: median 211 ns, p10 190, p90 251"
#include <immintrin.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "pin_to_cpu.hpp"

namespace {

enum class Mode { plain, clwb, flush, prefetch, reader_flush };

std::optional<Mode> mode_named(const std::string& name) {
  if (name == "plain") return Mode::plain;
  if (name == "clwb") return Mode::clwb;
  if (name == "flush") return Mode::flush;
  if (name == "prefetch") return Mode::prefetch;
  if (name == "reader-flush") return Mode::reader_flush;
  return std::nullopt;
}

struct alignas(64) Flag {
  std::atomic<long> value{0};
};

struct alignas(64) Line {
  double first;
  double rest[7];
};

}  // namespace

int main(int argc, char** argv) {
  const char* usage = "usage: line_handoff_probe LINES>=1 [HANDOFFS>=10] [MODE=plain|clwb|flush|prefetch|reader-flush]\n";
  if (argc < 2) {
    std::fputs(usage, stderr);
    return 2;
  }
  const long lines = std::atol(argv[1]);
  const long handoffs = argc > 2 ? std::atol(argv[2]) : 20000;
  const std::string name = argc > 3 ? argv[3] : "plain";
  const std::optional<Mode> named = mode_named(name);
  if (lines < 1 || handoffs < 10 || !named) {
    std::fputs(usage, stderr);
    return 2;
  }
  const Mode mode = *named;
  std::vector<Line> data(static_cast<std::size_t>(lines));
  Flag written, read;
  std::vector<double> ns(static_cast<std::size_t>(handoffs));
  std::atomic<bool> pinned{true};
  std::thread reader([&] {
    if (!pin_to(1)) pinned = false;
    double sum = 0;
    for (long k = 1; k <= handoffs; ++k) {
      while (written.value.load(std::memory_order_acquire) < k) _mm_pause();
      if (mode == Mode::prefetch)
        for (const Line& l : data) _mm_prefetch(reinterpret_cast<const char*>(&l), _MM_HINT_T0);
      for (const Line& l : data) sum += l.first;
      if (mode == Mode::reader_flush)
        for (Line& l : data) _mm_clflushopt(&l);
      read.value.store(k, std::memory_order_release);
    }
    if (sum < 0) std::puts("");  // keeps the reads
  });
  if (!pin_to(0)) pinned = false;
  for (long k = 1; k <= handoffs; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    for (long l = 0; l < lines; ++l) data[static_cast<std::size_t>(l)].first = static_cast<double>(k + l);
    if (mode == Mode::clwb || mode == Mode::flush) {
      for (Line& l : data) mode == Mode::clwb ? _mm_clwb(&l) : _mm_clflushopt(&l);
      _mm_sfence();
    }
    written.value.store(k, std::memory_order_release);
    while (read.value.load(std::memory_order_acquire) < k) _mm_pause();
    ns[static_cast<std::size_t>(k - 1)] = std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count();
  }
  reader.join();
  if (!pinned) {
    std::fprintf(stderr, "line_handoff_probe: could not pin to CPUs 0 and 1\n");
    return 1;
  }
  std::sort(ns.begin(), ns.end());
  const auto at = [&](double q) { return ns[static_cast<std::size_t>(q * (handoffs - 1))]; };
  std::printf("lines %ld mode %s: median %.0f ns, p10 %.0f, p90 %.0f\n", lines, name.c_str(), at(0.5), at(0.1), at(0.9));
  return 0;
}
