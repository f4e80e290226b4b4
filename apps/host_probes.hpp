// What the host gives two threads at the moment, read by `runout bench` beside its turns so that
// a two-thread figure says which state of the host it met (docs/performance.md, issue 11).
#pragma once

namespace runout::app {

// How long one cache line takes to go from the team's thread 0 to its thread 1 and back, in ns:
// the two pass a counter to and fro `trips` times. NaN when OpenMP gives fewer than two threads.
double line_round_trip_ns(long trips);

// Two threads' arithmetic over one thread's: the same loop, on registers and a few constants in
// L1, timed on the calling thread alone and on two threads at once (the better of two reads of
// each), as 2 × alone / together.
// About 2 when each thread has a core, or the same share of one, to itself; about 1 when the host
// has put them on the two hyperthreads of one core, where one thread alone runs nearly twice as
// fast as each of two; about 1 too when the two take turns on one CPU. It reads no data, so
// caches and the other thread's lines play no part.
// NaN when OpenMP gives fewer than two threads.
double arithmetic_pair_speedup(long rounds);

}  // namespace runout::app
