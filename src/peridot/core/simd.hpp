#pragma once
// Which instruction set the bond loops run with. The loops (solvers/internal_force.cpp, correspondence/
// kinematics.cpp and force.cpp) are compiled once per target with Google Highway's foreach_target and the
// best one this CPU runs is chosen at the first pass; the rest of the program is built for the baseline
// (x86-64-v2 on x86), so one binary runs on any CPU of the family. PERIDOT_SIMD=NAME in the environment
// forces a target (tests, benchmarks, a suspected miscompilation); docs/performance.md lists them.
#include <string>
#include <vector>

namespace peridot::simd {

/// The targets compiled into this binary that this CPU can run, best first: on x86 "avx512", "avx2",
/// "sse4" (the baseline), "scalar" (Highway's fallback, no vectors); on Arm "sve2", "sve", "neon" as built.
const std::vector<std::string>& available_targets();

/// The target the bond loops use now (PERIDOT_SIMD's, once read, or the best available).
std::string active_target();

/// Makes the bond loops use `name` (one of available_targets()) from now on; "" restores the best.
/// Throws std::invalid_argument naming the available targets when `name` is not one of them.
void force_target(const std::string& name);

/// Reads PERIDOT_SIMD once (later calls do nothing) and forces its target. Every dispatched pass calls
/// this first, so the variable works for the program, the tests, the benchmarks and the Python module.
/// Throws std::invalid_argument, as force_target, for a target this CPU or build lacks.
void apply_environment();

/// "avx512 (available: avx512, avx2, sse4; PERIDOT_SIMD forces one)", for run.log and `peridot info`.
std::string describe();

}  // namespace peridot::simd
