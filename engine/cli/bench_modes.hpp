#pragma once
// The modes of `hapscene bench` besides the default tick-cost tables, one file each:
//   --accuracy   run time against error of the simulated Hapkit (bench_accuracy.cpp)
//   --stress     stiffness and damping sweeps (bench_stress.cpp)
//   --soak       100 million ticks per lab environment (bench_soak.cpp)
//   --callgrind  a fixed number of ticks, untimed, for valgrind (bench_callgrind.cpp)
//   --realtime   the tick paced as the real loop runs it: sleep, wake, tick (bench_realtime.cpp)
#include "engine/cli/arguments.hpp"

namespace hapscene {

int bench_accuracy(Arguments& arguments);
int bench_stress(Arguments& arguments);
int bench_soak(Arguments& arguments);
int bench_callgrind(Arguments& arguments);
int bench_realtime(Arguments& arguments);

}  // namespace hapscene
